#include "io/detail/abaqus_surfaces.h"

#include <algorithm>
#include <cctype>
#include <charconv>

#include "core/error.h"

namespace tissuemesh::io::detail {
namespace {

using Key = std::array<std::uint32_t, 3>;

Key sorted(Key key)
{
    std::sort(key.begin(), key.end());
    return key;
}

std::string upper(std::string text)
{
    for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return text;
}

std::string surface_name(const LabelPair& pair) { return concat("IF_", pair.from, "_", pair.to); }

/// Which element face carries each mesh face: the tet of `from` that has it, else a tet of `to`.
std::vector<std::pair<std::size_t, int>> face_owners(const TetMesh& mesh, const std::string& what)
{
    std::vector<std::pair<Key, std::size_t>> lookup;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) lookup.push_back({sorted(mesh.faces[f]), f});
    std::sort(lookup.begin(), lookup.end());
    constexpr std::size_t none = static_cast<std::size_t>(-1);
    std::vector<std::pair<std::size_t, int>> owner(mesh.faces.size(), {none, 0});
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        for (int k = 1; k <= 4; ++k) {
            const auto& local = c3d4_face(k);
            const Key key = sorted({mesh.tets[t][local[0]], mesh.tets[t][local[1]], mesh.tets[t][local[2]]});
            for (auto it = std::lower_bound(lookup.begin(), lookup.end(), std::pair<Key, std::size_t>{key, 0});
                 it != lookup.end() && it->first == key; ++it) {
                const LabelPair& pair = mesh.face_sides[it->second];
                const bool from_side = mesh.tet_labels[t] == pair.from;
                if (from_side || (mesh.tet_labels[t] == pair.to && owner[it->second].first == none))
                    owner[it->second] = {t, k};
            }
        }
    for (std::size_t f = 0; f < owner.size(); ++f)
        if (owner[f].first == none)
            throw InputError(concat(
                what, ": face ", f, " (", mesh.face_sides[f].from, " | ", mesh.face_sides[f].to,
                ") is no face of a tet of either tissue, so Abaqus cannot hold it; check the mesh with tm-check-mesh"));
    return owner;
}

} // namespace

const std::array<std::size_t, 3>& c3d4_face(int k)
{
    static const std::array<std::array<std::size_t, 3>, 4> faces{{{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}}};
    return faces[static_cast<std::size_t>(std::clamp(k, 1, 4) - 1)];
}

std::string format_abaqus_surfaces(const TetMesh& mesh, const std::vector<long long>& element_of_tet,
                                   const std::string& what)
{
    const auto owner = face_owners(mesh, what);
    std::map<std::pair<Label, Label>, std::array<std::vector<long long>, 4>> members; // by pair, by face id
    for (std::size_t f = 0; f < owner.size(); ++f)
        members[{mesh.face_sides[f].from, mesh.face_sides[f].to}][static_cast<std::size_t>(owner[f].second - 1)]
            .push_back(element_of_tet[owner[f].first]);
    std::string out;
    for (auto& [labels, by_face] : members) {
        const std::string name = surface_name({labels.first, labels.second});
        out += concat("** tissuemesh surface ", name, " from ", labels.first, " to ", labels.second, "\n");
        for (std::size_t k = 0; k < 4; ++k) {
            if (by_face[k].empty()) continue;
            std::sort(by_face[k].begin(), by_face[k].end());
            out += concat("*ELSET, ELSET=", name, "_S", k + 1, "_ELEMS\n");
            for (std::size_t i = 0; i < by_face[k].size(); ++i)
                out += concat(by_face[k][i], i + 1 == by_face[k].size() || i % 16 == 15 ? "\n" : ", ");
        }
        out += concat("*SURFACE, TYPE=ELEMENT, NAME=", name, "\n");
        for (std::size_t k = 0; k < 4; ++k)
            if (!by_face[k].empty()) out += concat(name, "_S", k + 1, "_ELEMS, S", k + 1, "\n");
    }
    return out;
}

void add_abaqus_faces(TetMesh& mesh, const AbaqusFaceSources& sources, const ByteReader& in)
{
    std::map<std::string, const std::vector<long long>*> set_by_name;
    for (const auto& [name, elements] : sources.sets) set_by_name[upper(name)] = &elements;
    for (const AbaqusSurface& surface : sources.surfaces) {
        const auto commented = sources.pairs.find(upper(surface.name));
        for (const auto& [reference, k] : surface.entries) {
            if (k < 1 || k > 4)
                in.fail(concat("surface ", surface.name, " names face S", k, " of a C3D4 element"),
                        "use S1, S2, S3 or S4");
            std::vector<long long> single;
            const std::vector<long long>* elements = nullptr;
            long long number = 0;
            if (std::from_chars(reference.data(), reference.data() + reference.size(), number).ptr ==
                reference.data() + reference.size()) {
                single.push_back(number);
                elements = &single;
            } else if (const auto found = set_by_name.find(upper(reference)); found != set_by_name.end()) {
                elements = found->second;
            } else {
                in.fail(
                    concat("surface ", surface.name, " refers to element set ", reference, ", which is not defined"),
                    "define it with *ELSET");
            }
            for (const long long element : *elements) {
                const auto tet = sources.tet_of.find(element);
                if (tet == sources.tet_of.end()) continue; // not a tetrahedron: not read
                const Tet& c = sources.corners[tet->second];
                const auto& local = c3d4_face(k);
                Triangle face{c[local[0]], c[local[1]], c[local[2]]};
                const std::uint32_t opposite = c[6 - local[0] - local[1] - local[2]];
                const Vec3 &a = mesh.vertices[face[0]], &b = mesh.vertices[face[1]], &d = mesh.vertices[face[2]],
                           &o = mesh.vertices[opposite];
                if (dot(cross(b - a, d - a), o - a) > 0) std::swap(face[1], face[2]); // now out of the element
                const Label label = mesh.tet_labels[tet->second];
                LabelPair pair{label, 0};
                if (commented != sources.pairs.end()) {
                    pair = commented->second;
                    if (label == pair.to && label != pair.from)
                        std::swap(face[1], face[2]); // the element lies on the `to` side
                }
                mesh.faces.push_back(face);
                mesh.face_sides.push_back(pair);
            }
            if (mesh.faces.size() > 4 * mesh.tets.size())
                in.fail(concat("the surfaces list more faces than the ", mesh.tets.size(), " tets have"),
                        "the file is corrupt; write it again");
        }
    }
}

} // namespace tissuemesh::io::detail

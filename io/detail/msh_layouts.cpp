#include "io/detail/msh_layouts.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "core/error.h"
#include "io/simnibs_tags.h"

namespace tissuemesh::io::detail {
namespace {

/// One face of a tet: its sorted vertices, the tet, and the corner opposite it.
struct TetFace {
    std::array<std::uint32_t, 3> key;
    std::uint32_t tet;
    std::uint8_t opposite;
    bool operator<(const TetFace& other) const { return key != other.key ? key < other.key : tet < other.tet; }
};

/// The face of positively oriented `tet` opposite corner `k`, wound so that its normal points out of the tet.
Triangle outward_face(const Tet& tet, std::uint8_t k)
{
    switch (k) {
    case 0: return {tet[1], tet[2], tet[3]};
    case 1: return {tet[0], tet[3], tet[2]};
    case 2: return {tet[0], tet[1], tet[3]};
    default: return {tet[0], tet[2], tet[1]};
    }
}

std::vector<TetFace> sorted_tet_faces(const TetMesh& mesh)
{
    std::vector<TetFace> faces;
    faces.reserve(4 * mesh.tets.size());
    for (std::uint32_t t = 0; t < mesh.tets.size(); ++t)
        for (std::uint8_t k = 0; k < 4; ++k) {
            Triangle key = outward_face(mesh.tets[t], k);
            std::sort(key.begin(), key.end());
            faces.push_back({key, t, k});
        }
    std::sort(faces.begin(), faces.end());
    return faces;
}

std::string without_spaces(std::string name)
{
    std::replace(name.begin(), name.end(), ' ', '_');
    std::replace(name.begin(), name.end(), '"', '\'');
    return name;
}

std::string name_of(const TetMesh& mesh, Label label)
{
    const auto found = mesh.names.find(label);
    return found != mesh.names.end() ? found->second : std::to_string(label);
}

/// $PhysicalNames for volume and surface tags: SimNIBS's own name where the tag is standard, else the tissue's.
std::string simnibs_names(const TetMesh& mesh, const std::map<Label, int>& tags, const std::set<int>& face_tags)
{
    std::map<int, std::string> names;
    for (const auto& [label, tag] : tags) names[tag] = without_spaces(name_of(mesh, label));
    for (const SimnibsTissue& tissue : simnibs_tissues()) names[tissue.tag] = tissue.name;
    std::set<int> volume_tags;
    for (const auto& [label, tag] : tags) volume_tags.insert(tag);
    std::string out = concat("$PhysicalNames\n", volume_tags.size() + face_tags.size(), "\n");
    for (const int tag : face_tags)
        out += concat("2 ", tag, " \"", names.count(tag - 1000) ? names[tag - 1000] : "outer", "_surface\"\n");
    for (const int tag : volume_tags) out += concat("3 ", tag, " \"", names[tag], "\"\n");
    return out + "$EndPhysicalNames\n";
}

} // namespace

Msh2Elements simnibs_elements(const TetMesh& mesh, const std::map<Label, int>& tags)
{
    std::vector<Triangle> faces;
    std::vector<std::array<int, 2>> face_tags;
    std::set<int> used_face_tags;
    const std::vector<TetFace> all = sorted_tet_faces(mesh);
    const auto tag_of = [&](std::uint32_t tet) { return tags.at(mesh.tet_labels[tet]); };
    for (std::size_t i = 0; i < all.size();) {
        std::size_t end = i + 1;
        while (end < all.size() && all[end].key == all[i].key) ++end;
        if (end - i > 2)
            throw InputError(concat("a face is shared by ", end - i, " tets (nodes ", all[i].key[0] + 1, ", ",
                                    all[i].key[1] + 1, ", ", all[i].key[2] + 1,
                                    "); the mesh does not conform, check it with tm-check-mesh"));
        int tag = 1005;
        const TetFace* owner = &all[i];
        if (end - i == 2) {
            const int a = tag_of(all[i].tet), b = tag_of(all[i + 1].tet);
            if (a == b) {
                i = end;
                continue;
            }
            tag = simnibs_face_tag(a, b);
            if (tag - 1000 != a) owner = &all[i + 1];
        }
        faces.push_back(outward_face(mesh.tets[owner->tet], owner->opposite));
        face_tags.push_back({tag, tag});
        used_face_tags.insert(tag);
        i = end;
    }
    Msh2Elements elements{.faces = {},
                          .face_tags = std::move(face_tags),
                          .tets = mesh.tets,
                          .tet_tags = {},
                          .physical_names = simnibs_names(mesh, tags, used_face_tags),
                          .names_after_elements = false};
    for (const Label label : mesh.tet_labels) elements.tet_tags.push_back({tags.at(label), tags.at(label)});
    // The faces are new: keep them alive with the elements (the span points into this member).
    elements.owned_faces = std::move(faces);
    elements.faces = elements.owned_faces;
    return elements;
}

Msh2Elements duneuro_elements(const TetMesh& mesh, int offset)
{
    const std::set<Label> labels(mesh.tet_labels.begin(), mesh.tet_labels.end());
    std::map<Label, int> tag;
    std::string names = concat("$PhysicalNames\n", labels.size(), "\n");
    for (const Label label : labels) {
        tag[label] = offset + static_cast<int>(tag.size());
        names += concat("3 ", tag[label], " \"", without_spaces(name_of(mesh, label)), "\"\n");
    }
    Msh2Elements elements{.faces = {},
                          .face_tags = {},
                          .tets = mesh.tets,
                          .tet_tags = {},
                          .physical_names = names + "$EndPhysicalNames\n",
                          .names_after_elements = true};
    for (const Label label : mesh.tet_labels) elements.tet_tags.push_back({tag[label], tag[label]});
    return elements;
}

std::string duneuro_conductivity_file(const TetMesh& mesh, const std::map<Label, double>& conductivities)
{
    const std::set<Label> labels(mesh.tet_labels.begin(), mesh.tet_labels.end());
    std::string out;
    char line[40];
    for (const Label label : labels) {
        const auto found = conductivities.find(label);
        if (found == conductivities.end() || !(found->second > 0) || !std::isfinite(found->second))
            throw InputError(concat("tissue \"", name_of(mesh, label), "\" (label ", label,
                                    ") has no positive conductivity for "
                                    "DUNEuro; give it one in the conductivity table (--conductivity)"));
        out.append(line, static_cast<std::size_t>(std::snprintf(line, sizeof line, "%.17g\n", found->second)));
    }
    return out;
}

} // namespace tissuemesh::io::detail

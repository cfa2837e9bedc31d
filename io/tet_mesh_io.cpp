#include "io/tet_mesh_io.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/write_vtu.h"

namespace tissuemesh::io {
namespace fs = std::filesystem;
namespace {

int face_tag(const LabelPair& pair) { return 1000 * pair.from + pair.to; }
LabelPair pair_of_tag(int tag) { return {static_cast<Label>(tag / 1000), static_cast<Label>(tag % 1000)}; }

void write_msh(const TetMesh& mesh, std::ostream& out)
{
    out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
    std::set<Label> tissues(mesh.tet_labels.begin(), mesh.tet_labels.end());
    std::set<Label> face_groups;
    for (const LabelPair& pair : mesh.face_sides) face_groups.insert(pair.from);
    out << "$PhysicalNames\n" << tissues.size() + face_groups.size() << "\n";
    auto name = [&](Label label) {
        const auto found = mesh.names.find(label);
        return found != mesh.names.end() ? found->second : std::to_string(label);
    };
    for (const Label label : face_groups) out << "2 " << 1000 + label << " \"" << name(label) << " boundary\"\n";
    for (const Label label : tissues) out << "3 " << label << " \"" << name(label) << "\"\n";
    out << "$EndPhysicalNames\n$Nodes\n" << mesh.vertices.size() << "\n";
    out << std::setprecision(17);
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
        out << v + 1 << ' ' << mesh.vertices[v][0] << ' ' << mesh.vertices[v][1] << ' ' << mesh.vertices[v][2] << '\n';
    out << "$EndNodes\n$Elements\n" << mesh.faces.size() + mesh.tets.size() << "\n";
    std::size_t id = 1;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const Triangle& tri = mesh.faces[f];
        out << id++ << " 2 2 " << 1000 + mesh.face_sides[f].from << ' ' << face_tag(mesh.face_sides[f]) << ' '
            << tri[0] + 1 << ' ' << tri[1] + 1 << ' ' << tri[2] + 1 << '\n';
    }
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& tet = mesh.tets[t];
        out << id++ << " 4 2 " << mesh.tet_labels[t] << ' ' << mesh.tet_labels[t] << ' ' << tet[0] + 1 << ' '
            << tet[1] + 1 << ' ' << tet[2] + 1 << ' ' << tet[3] + 1 << '\n';
    }
    out << "$EndElements\n";
}

void write_medit(const TetMesh& mesh, std::ostream& out)
{
    out << "MeshVersionFormatted 2\nDimension 3\nVertices\n" << mesh.vertices.size() << "\n" << std::setprecision(17);
    for (const Vec3& v : mesh.vertices) out << v[0] << ' ' << v[1] << ' ' << v[2] << " 0\n";
    out << "Triangles\n" << mesh.faces.size() << "\n";
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
        out << mesh.faces[f][0] + 1 << ' ' << mesh.faces[f][1] + 1 << ' ' << mesh.faces[f][2] + 1 << ' '
            << face_tag(mesh.face_sides[f]) << '\n';
    out << "Tetrahedra\n" << mesh.tets.size() << "\n";
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        out << mesh.tets[t][0] + 1 << ' ' << mesh.tets[t][1] + 1 << ' ' << mesh.tets[t][2] + 1 << ' '
            << mesh.tets[t][3] + 1 << ' ' << mesh.tet_labels[t] << '\n';
    out << "End\n";
}

/// Token reader with the file name and a clear message on malformed input.
class Tokens {
public:
    Tokens(const fs::path& path) : path_(path), in_(path) {}
    template <typename T>
    T next(const char* what)
    {
        T value{};
        if (!(in_ >> value)) throw IoError(concat(path_.string(), ": expected ", what, "; the file is truncated or malformed"));
        return value;
    }
    std::string word() { std::string w; in_ >> w; return w; }
    void skip_line() { in_.ignore(std::numeric_limits<std::streamsize>::max(), '\n'); }
    bool good() const { return static_cast<bool>(in_); }

private:
    fs::path path_;
    std::ifstream in_;
};

std::size_t checked_count(Tokens& in, const fs::path& path, const char* what)
{
    const long long count = in.next<long long>(what);
    if (count < 0 || count > (1LL << 31))
        throw IoError(concat(path.string(), ": ", count, " ", what, " is not a plausible count; the file is corrupt"));
    return static_cast<std::size_t>(count);
}

TetMesh read_msh(const fs::path& path)
{
    Tokens in(path);
    TetMesh mesh;
    if (in.word() != "$MeshFormat") throw IoError(concat(path.string(), ": not a Gmsh file (no $MeshFormat)"));
    const double version = in.next<double>("a format version");
    const int binary = in.next<int>("the file type");
    if (version < 2 || version >= 3 || binary != 0)
        throw IoError(concat(path.string(), ": Gmsh format ", version, binary ? " binary" : "", " is not supported; "
                             "save as version 2.2 ASCII (gmsh -format msh22)"));
    std::vector<long long> ids;
    for (std::string section = in.word(); in.good() && !section.empty(); section = in.word()) {
        if (section == "$Nodes") {
            const std::size_t count = checked_count(in, path, "nodes");
            mesh.vertices.resize(count);
            ids.resize(count);
            for (std::size_t v = 0; v < count; ++v) {
                ids[v] = in.next<long long>("a node number");
                for (double& c : mesh.vertices[v]) c = in.next<double>("a coordinate");
            }
        } else if (section == "$Elements") {
            const std::size_t count = checked_count(in, path, "elements");
            // Node numbers are usually 1..N: a direct table; sparse numbering falls back to a map.
            const long long max_id = ids.empty() ? 0 : *std::max_element(ids.begin(), ids.end());
            const bool dense = max_id >= 0 && static_cast<std::size_t>(max_id) <= 4 * ids.size() + 16;
            constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
            std::vector<std::uint32_t> table(dense ? static_cast<std::size_t>(max_id) + 1 : 0, none);
            std::map<long long, std::uint32_t> index;
            for (std::size_t v = 0; v < ids.size(); ++v) {
                if (dense && ids[v] >= 0) table[static_cast<std::size_t>(ids[v])] = static_cast<std::uint32_t>(v);
                else index[ids[v]] = static_cast<std::uint32_t>(v);
            }
            auto node = [&](long long id) {
                if (dense && id >= 0 && id <= max_id && table[static_cast<std::size_t>(id)] != none)
                    return table[static_cast<std::size_t>(id)];
                const auto found = index.find(id);
                if (found == index.end())
                    throw InputError(concat(path.string(), ": an element refers to node ", id, ", which does not exist"));
                return found->second;
            };
            for (std::size_t e = 0; e < count; ++e) {
                in.next<long long>("an element number");
                const int type = in.next<int>("an element type");
                const int tag_count = in.next<int>("a tag count");
                std::vector<int> tags(std::max(tag_count, 0));
                for (int& tag : tags) tag = in.next<int>("a tag");
                const int nodes = type == 4 ? 4 : type == 2 ? 3 : type == 1 ? 2 : type == 15 ? 1 : -1;
                if (nodes < 0) throw IoError(concat(path.string(), ": element type ", type, " is not supported (tets, triangles)"));
                std::array<std::uint32_t, 4> v{};
                for (int c = 0; c < nodes; ++c) v[c] = node(in.next<long long>("a node number"));
                const int physical = tags.empty() ? 0 : tags[0];
                if (type == 4) {
                    mesh.tets.push_back({v[0], v[1], v[2], v[3]});
                    mesh.tet_labels.push_back(static_cast<Label>(physical));
                } else if (type == 2) {
                    mesh.faces.push_back({v[0], v[1], v[2]});
                    mesh.face_sides.push_back(tags.size() > 1 && tags[1] >= 1000 ? pair_of_tag(tags[1])
                                                                                   : LabelPair{static_cast<Label>(physical % 1000), 0});
                }
            }
        } else if (section == "$PhysicalNames") {
            const std::size_t count = checked_count(in, path, "physical names");
            for (std::size_t n = 0; n < count; ++n) {
                const int dim = in.next<int>("a dimension");
                const int tag = in.next<int>("a physical tag");
                std::string quoted = in.word();
                while (!quoted.empty() && quoted.back() != '"' && in.good()) {
                    quoted.push_back(' ');
                    quoted.append(in.word());
                }
                if (dim == 3 && tag >= 0 && tag <= 65535 && quoted.size() >= 2)
                    mesh.names[static_cast<Label>(tag)] = quoted.substr(1, quoted.size() - 2);
            }
        }
        // Other sections ($NodeData, ...) are skipped word by word: their words match no section name.
    }
    validate_indices(mesh, path.string());
    return mesh;
}

TetMesh read_medit(const fs::path& path)
{
    Tokens in(path);
    TetMesh mesh;
    if (in.word() != "MeshVersionFormatted") throw IoError(concat(path.string(), ": not a Medit .mesh file"));
    in.next<int>("a version");
    for (std::string keyword = in.word(); in.good() && keyword != "End" && !keyword.empty(); keyword = in.word()) {
        if (keyword == "Dimension") {
            if (in.next<int>("a dimension") != 3) throw IoError(concat(path.string(), ": only 3-D meshes are supported"));
        } else if (keyword == "Vertices") {
            mesh.vertices.resize(checked_count(in, path, "vertices"));
            for (Vec3& v : mesh.vertices) {
                for (double& c : v) c = in.next<double>("a coordinate");
                in.next<int>("a vertex reference");
            }
        } else if (keyword == "Triangles" || keyword == "Tetrahedra") {
            const bool tets = keyword == "Tetrahedra";
            const std::size_t count = checked_count(in, path, tets ? "tetrahedra" : "triangles");
            for (std::size_t e = 0; e < count; ++e) {
                std::array<std::uint32_t, 4> v{};
                for (int c = 0; c < (tets ? 4 : 3); ++c) {
                    const long long index = in.next<long long>("a vertex index");
                    if (index < 1) throw InputError(concat(path.string(), ": vertex index ", index, " is below 1"));
                    v[c] = static_cast<std::uint32_t>(index - 1);
                }
                const int reference = in.next<int>("an element reference");
                if (tets) {
                    mesh.tets.push_back(v);
                    mesh.tet_labels.push_back(static_cast<Label>(reference));
                } else {
                    mesh.faces.push_back({v[0], v[1], v[2]});
                    mesh.face_sides.push_back(pair_of_tag(reference));
                }
            }
        } else {
            throw IoError(concat(path.string(), ": section \"", keyword, "\" is not supported"));
        }
    }
    validate_indices(mesh, path.string());
    return mesh;
}

} // namespace

void write_tet_mesh(const TetMesh& mesh, const fs::path& path)
{
    const std::string extension = full_extension(path);
    if (extension != ".msh" && extension != ".mesh" && extension != ".vtu")
        throw IoError(concat(path.string(), ": unknown mesh format \"", extension, "\"; use .msh, .mesh or .vtu"));
    if (extension == ".vtu") return write_vtu(mesh, path);
    write_atomically(path, [&](const fs::path& temporary) {
        std::ofstream out(temporary);
        if (!out) throw IoError(concat(path.string(), ": cannot open for writing; check the permissions"));
        if (extension == ".msh") write_msh(mesh, out);
        else write_medit(mesh, out);
        out.close();
        if (!out) throw IoError(concat(path.string(), ": write failed (disk full?)"));
    });
}

TetMesh read_tet_mesh(const fs::path& path)
{
    require_readable_file(path);
    const std::string extension = full_extension(path);
    if (extension == ".msh") return read_msh(path);
    if (extension == ".mesh") return read_medit(path);
    throw IoError(concat(path.string(), ": cannot read meshes of type \"", extension, "\"; use .msh or .mesh"));
}

} // namespace tissuemesh::io

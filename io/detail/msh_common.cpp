#include "io/detail/msh_common.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <set>

#include "core/error.h"

namespace tissuemesh::io::detail {

LabelPair face_pair(int physical, int elementary)
{
    if (physical >= 1000 && physical - 1000 <= 65535) {
        const int from = physical - 1000;
        const long long to = static_cast<long long>(elementary) - 1000LL * from;
        return {static_cast<Label>(from), static_cast<Label>(to >= 0 && to <= 65535 ? to : 0)};
    }
    if (elementary >= 1000) return single_tag_pair(elementary);
    return {static_cast<Label>(std::clamp(physical, 0, 65535)), 0};
}

LabelPair single_tag_pair(long long tag)
{
    if (tag < 0 || tag / 1000 > 65535) return {0, 0};
    return {static_cast<Label>(tag / 1000), static_cast<Label>(tag % 1000)};
}

std::string format_physical_names(const TetMesh& mesh)
{
    const std::set<Label> tissues(mesh.tet_labels.begin(), mesh.tet_labels.end());
    std::set<Label> face_groups;
    for (const LabelPair& pair : mesh.face_sides) face_groups.insert(pair.from);
    auto name = [&](Label label) {
        const auto found = mesh.names.find(label);
        return found != mesh.names.end() ? found->second : std::to_string(label);
    };
    std::string out = concat("$PhysicalNames\n", tissues.size() + face_groups.size(), "\n");
    for (const Label label : face_groups) out += concat("2 ", 1000 + label, " \"", name(label), " boundary\"\n");
    for (const Label label : tissues) out += concat("3 ", label, " \"", name(label), "\"\n");
    return out + "$EndPhysicalNames\n";
}

void parse_physical_names(ByteReader& in, TissueNames& names)
{
    const std::size_t count = in.count("physical names", 6);
    for (std::size_t n = 0; n < count; ++n) {
        const long long dim = in.integer("a physical dimension");
        const long long tag = in.integer("a physical tag");
        std::string line(in.rest_of_line());
        const std::size_t open = line.find('"'), close = line.rfind('"');
        if (open == std::string::npos || close == open) in.fail("a physical name is not quoted", "the file is corrupt");
        if (dim == 3 && tag >= 0 && tag <= 65535)
            names[static_cast<Label>(tag)] = line.substr(open + 1, close - open - 1);
    }
}

void NodeIndex::finish(const ByteReader& in)
{
    long long max_tag = 0;
    bool positive = true;
    for (const long long tag : tags_) max_tag = std::max(max_tag, tag), positive = positive && tag > 0;
    constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
    if (positive && static_cast<unsigned long long>(max_tag) <= 4 * tags_.size() + 16) {
        dense_.assign(static_cast<std::size_t>(max_tag) + 1, none);
        for (std::size_t v = 0; v < tags_.size(); ++v) {
            std::uint32_t& slot = dense_[static_cast<std::size_t>(tags_[v])];
            if (slot != none) in.fail(concat("node ", tags_[v], " is defined twice"), "the file is corrupt");
            slot = static_cast<std::uint32_t>(v);
        }
    } else {
        for (std::size_t v = 0; v < tags_.size(); ++v)
            if (!sparse_.emplace(tags_[v], static_cast<std::uint32_t>(v)).second)
                in.fail(concat("node ", tags_[v], " is defined twice"), "the file is corrupt");
    }
}

std::uint32_t NodeIndex::at(long long tag, const ByteReader& in) const
{
    constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
    if (!dense_.empty() && tag >= 0 && static_cast<std::size_t>(tag) < dense_.size() &&
        dense_[static_cast<std::size_t>(tag)] != none)
        return dense_[static_cast<std::size_t>(tag)];
    if (const auto found = sparse_.find(tag); found != sparse_.end()) return found->second;
    throw InputError(concat(in.what(), ": an element refers to node ", tag, ", which does not exist (at byte ",
                            in.position(), "); the file is corrupt, write it again"));
}

int gmsh_element_nodes(int type)
{
    switch (type) {
    case 15: return 1;  // point
    case 1: return 2;   // line
    case 2: return 3;   // triangle
    case 3: return 4;   // quadrangle
    case 4: return 4;   // tetrahedron
    case 5: return 8;   // hexahedron
    case 6: return 6;   // prism
    case 7: return 5;   // pyramid
    case 8: return 3;   // second-order line
    case 9: return 6;   // second-order triangle
    case 10: return 9;  // second-order quadrangle
    case 11: return 10; // second-order tetrahedron
    default: return -1;
    }
}

void add_tet(TetMesh& mesh, const std::array<std::uint32_t, 4>& v, Label label)
{
    mesh.tets.push_back(v);
    mesh.tet_labels.push_back(label);
    // Orientation needs the vertices: callers read nodes before elements, as every format here stores them.
    const std::size_t t = mesh.tets.size() - 1;
    const bool known = v[0] < mesh.vertices.size() && v[1] < mesh.vertices.size() && v[2] < mesh.vertices.size() &&
                       v[3] < mesh.vertices.size();
    if (known && signed_volume(mesh, t) < 0) std::swap(mesh.tets[t][2], mesh.tets[t][3]);
}

void append_real(std::string& out, double value)
{
    char buffer[32];
    const int length = std::snprintf(buffer, sizeof(buffer), "%.17g", value);
    out.append(buffer, static_cast<std::size_t>(length));
}

bool parse_mesh_format(ByteReader& in, const char* data_size_hint)
{
    const long long file_type = in.integer("the file type");
    const long long data_size = in.integer("the data size");
    if (file_type != 0 && file_type != 1)
        in.fail(concat("file type ", file_type, " is neither 0 nor 1"), "the file is corrupt");
    const bool binary = file_type == 1;
    if (binary) {
        if (data_size != 8) in.fail(concat("data size ", data_size, " is not 8"), data_size_hint);
        in.skip_line();
        if (in.binary<std::int32_t>("the byte-order mark") != 1)
            in.fail("the byte-order mark is not 1", "the file was written big-endian; convert it with gmsh");
    }
    in.expect("$EndMeshFormat");
    return binary;
}

} // namespace tissuemesh::io::detail

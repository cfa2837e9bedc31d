#include "io/detail/msh2_format.h"

#include <bit>
#include <cstdint>

#include "core/error.h"
#include "io/detail/msh_common.h"

namespace tissuemesh::io::detail {
namespace {

static_assert(std::endian::native == std::endian::little, "binary .msh code assumes a little-endian host");

void append_elements_ascii(std::string& out, const Msh2Elements& elements)
{
    std::size_t id = 1;
    for (std::size_t f = 0; f < elements.faces.size(); ++f) {
        const Triangle& tri = elements.faces[f];
        out += concat(id++, " 2 2 ", elements.face_tags[f][0], ' ', elements.face_tags[f][1], ' ', tri[0] + 1, ' ',
                      tri[1] + 1, ' ', tri[2] + 1, '\n');
    }
    for (std::size_t t = 0; t < elements.tets.size(); ++t) {
        const Tet& tet = elements.tets[t];
        out += concat(id++, " 4 2 ", elements.tet_tags[t][0], ' ', elements.tet_tags[t][1], ' ', tet[0] + 1, ' ',
                      tet[1] + 1, ' ', tet[2] + 1, ' ', tet[3] + 1, '\n');
    }
}

/// One block of elements of one type with two tags each: header (type, count, tags), then per element its
/// number, tags and nodes, all int32.
template <std::size_t Corners>
void append_block_binary(std::string& out, int type, std::span<const std::array<std::uint32_t, Corners>> cells,
                         const std::vector<std::array<int, 2>>& tags, int& id)
{
    if (cells.empty()) return;
    for (const int value : {type, static_cast<int>(cells.size()), 2}) append_binary<std::int32_t>(out, value);
    for (std::size_t c = 0; c < cells.size(); ++c) {
        for (const int value : {id++, tags[c][0], tags[c][1]}) append_binary<std::int32_t>(out, value);
        for (const std::uint32_t v : cells[c]) append_binary<std::int32_t>(out, static_cast<std::int32_t>(v + 1));
    }
}

/// One element's type, tags and node numbers -> a face or tet of `mesh` (others are dropped).
void add_element(TetMesh& mesh, int type, const std::vector<int>& tags, const std::array<std::uint32_t, 4>& v)
{
    const int physical = tags.empty() ? 0 : tags[0];
    if (type == 4) {
        if (physical < 0 || physical > 65535)
            throw InputError(concat("tet physical tag ", physical, " is not a label"));
        add_tet(mesh, v, static_cast<Label>(physical));
    } else if (type == 2) {
        mesh.faces.push_back({v[0], v[1], v[2]});
        mesh.face_sides.push_back(face_pair(physical, tags.size() > 1 ? tags[1] : 0));
    }
}

void parse_elements_ascii(ByteReader& in, TetMesh& mesh, const NodeIndex& nodes)
{
    const std::size_t count = in.count("elements", 8);
    for (std::size_t e = 0; e < count; ++e) {
        in.integer("an element number");
        const auto type = static_cast<int>(in.integer("an element type"));
        const int corners = gmsh_element_nodes(type);
        if (corners < 0) in.fail(concat("element type ", type, " is not supported"), "save tets and triangles only");
        const std::size_t tag_count = in.count("element tags", 2);
        std::vector<int> tags(tag_count);
        for (int& tag : tags) tag = static_cast<int>(in.integer("an element tag"));
        std::array<std::uint32_t, 4> v{};
        for (int c = 0; c < corners; ++c) {
            const std::uint32_t vertex = nodes.at(in.integer("a node number"), in);
            if (c < 4) v[static_cast<std::size_t>(c)] = vertex;
        }
        add_element(mesh, type, tags, v);
    }
}

void parse_elements_binary(ByteReader& in, TetMesh& mesh, const NodeIndex& nodes)
{
    const std::size_t count = in.count("elements", 12);
    in.skip_line();
    for (std::size_t done = 0; done < count;) {
        const auto type = in.binary<std::int32_t>("an element type");
        const int corners = gmsh_element_nodes(type);
        if (corners < 0) in.fail(concat("element type ", type, " is not supported"), "save tets and triangles only");
        const std::size_t block = in.binary_count<std::int32_t>("elements in a block", 0);
        const std::size_t tag_count = in.binary_count<std::int32_t>("element tags", 4);
        const std::size_t element_bytes = 4 * (1 + tag_count + static_cast<std::size_t>(corners));
        if (block == 0 || block > count - done || block > in.remaining() / element_bytes)
            in.fail(concat(block, " elements announced in a block of ", count, " elements"),
                    "the file is truncated or corrupt; write it again");
        std::vector<int> tags(tag_count);
        for (std::size_t e = 0; e < block; ++e) {
            in.binary<std::int32_t>("an element number");
            for (int& tag : tags) tag = in.binary<std::int32_t>("an element tag");
            std::array<std::uint32_t, 4> v{};
            for (int c = 0; c < corners; ++c) {
                const std::uint32_t vertex = nodes.at(in.binary<std::int32_t>("a node number"), in);
                if (c < 4) v[static_cast<std::size_t>(c)] = vertex;
            }
            add_element(mesh, type, tags, v);
        }
        done += block;
    }
}

} // namespace

std::string format_msh2(const std::vector<Vec3>& vertices, const Msh2Elements& elements, bool binary)
{
    std::string out = binary ? "$MeshFormat\n2.2 1 8\n" : "$MeshFormat\n2.2 0 8\n";
    if (binary) append_binary<std::int32_t>(out, 1), out += '\n';
    out += "$EndMeshFormat\n";
    if (!elements.names_after_elements) out += elements.physical_names;
    out += concat("$Nodes\n", vertices.size(), "\n");
    for (std::size_t v = 0; v < vertices.size(); ++v) {
        if (binary) {
            append_binary<std::int32_t>(out, static_cast<std::int32_t>(v + 1));
            for (const double c : vertices[v]) append_binary<double>(out, c);
            continue;
        }
        out += concat(v + 1);
        for (const double c : vertices[v]) out += ' ', append_real(out, c);
        out += '\n';
    }
    out += binary ? "\n$EndNodes\n" : "$EndNodes\n";
    out += concat("$Elements\n", elements.faces.size() + elements.tets.size(), "\n");
    if (binary) {
        int id = 1;
        append_block_binary<3>(out, 2, elements.faces, elements.face_tags, id);
        append_block_binary<4>(out, 4, elements.tets, elements.tet_tags, id);
        out += '\n';
    } else {
        append_elements_ascii(out, elements);
    }
    out += "$EndElements\n";
    if (elements.names_after_elements) out += elements.physical_names;
    return out;
}

std::string format_msh2(const TetMesh& mesh, bool binary)
{
    Msh2Elements elements{.faces = mesh.faces,
                          .face_tags = {},
                          .tets = mesh.tets,
                          .tet_tags = {},
                          .physical_names = format_physical_names(mesh),
                          .names_after_elements = false};
    for (const LabelPair& pair : mesh.face_sides) elements.face_tags.push_back({face_physical(pair), face_tag(pair)});
    for (const Label label : mesh.tet_labels) elements.tet_tags.push_back({int{label}, int{label}});
    return format_msh2(mesh.vertices, elements, binary);
}

TetMesh parse_msh2(ByteReader& in)
{
    const bool binary = parse_mesh_format(in, "save with 8-byte doubles");
    TetMesh mesh;
    NodeIndex nodes;
    bool have_nodes = false;
    for (std::string_view section = in.word(); !section.empty(); section = in.word()) {
        if (section == "$Nodes") {
            const std::size_t count = in.count("nodes", binary ? 28 : 8);
            if (binary) in.skip_line();
            mesh.vertices.resize(count);
            nodes.reserve(count);
            for (Vec3& vertex : mesh.vertices) {
                nodes.add(binary ? in.binary<std::int32_t>("a node number") : in.integer("a node number"));
                for (double& c : vertex) c = binary ? in.binary<double>("a coordinate") : in.real("a coordinate");
            }
            nodes.finish(in);
            have_nodes = true;
            in.expect("$EndNodes");
        } else if (section == "$Elements") {
            if (!have_nodes) in.fail("$Elements comes before $Nodes", "the file is corrupt; write it again");
            if (binary) parse_elements_binary(in, mesh, nodes);
            else parse_elements_ascii(in, mesh, nodes);
            in.expect("$EndElements");
        } else if (section == "$PhysicalNames") {
            parse_physical_names(in, mesh.names);
            in.expect("$EndPhysicalNames");
        } else if (section.size() > 1 && section[0] == '$') {
            in.skip_past(concat("$End", section.substr(1))); // $NodeData, $Periodic, ...: not ours
        } else {
            in.fail(concat("unexpected \"", section.substr(0, 40), "\" between sections"),
                    "the file is corrupt; write it again");
        }
    }
    return mesh;
}

} // namespace tissuemesh::io::detail

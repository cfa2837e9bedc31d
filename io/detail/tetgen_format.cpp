#include "io/detail/tetgen_format.h"

#include "core/error.h"
#include "io/detail/byte_reader.h"
#include "io/detail/msh_common.h"
#include "io/detail/text_records.h"

namespace tissuemesh::io::detail {
namespace {

/// Node numbers of a record, from the file's base (0 or 1).
std::uint32_t node_of(ByteReader& in, long long base, std::size_t nodes)
{
    const long long number = in.integer("a node number");
    if (number < base || static_cast<unsigned long long>(number - base) >= nodes)
        throw InputError(concat(in.what(), ": node ", number, " does not exist (", nodes, " nodes from ", base,
                                ", at byte ", in.position(), "); the files do not belong together or are corrupt"));
    return static_cast<std::uint32_t>(number - base);
}

long long parse_nodes(const std::string& text, const std::string& what, TetMesh& mesh)
{
    const std::string clean = without_comments(text, "#");
    ByteReader in(clean, what + ".node");
    const std::size_t count = in.count("nodes", 8);
    if (in.integer("the dimension") != 3) in.fail("the nodes are not 3-D", "write a 3-D mesh");
    in.count("node attributes", 0);
    in.count("boundary-marker flags", 0);
    in.skip_line();
    mesh.vertices.resize(count);
    long long base = 0;
    for (std::size_t v = 0; v < count; ++v) {
        const long long number = in.integer("a node number");
        if (v == 0) base = number;
        if (base != 0 && base != 1) in.fail(concat("the first node is numbered ", base), "number nodes from 0 or 1");
        if (number != base + static_cast<long long>(v))
            in.fail(concat("node ", number, " is out of sequence (expected ", base + static_cast<long long>(v), ")"),
                    "number the nodes consecutively");
        for (double& c : mesh.vertices[v]) c = in.real("a coordinate");
        in.skip_line();
    }
    return base;
}

} // namespace

TetgenFiles format_tetgen(const TetMesh& mesh)
{
    TetgenFiles files;
    files.node = concat(mesh.vertices.size(), " 3 0 0\n");
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        files.node += concat(v + 1);
        for (const double c : mesh.vertices[v]) files.node += ' ', append_real(files.node, c);
        files.node += '\n';
    }
    files.ele = format_name_comments(mesh.names, "#") + concat(mesh.tets.size(), " 4 1\n");
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& tet = mesh.tets[t];
        files.ele += concat(t + 1, ' ', tet[0] + 1, ' ', tet[1] + 1, ' ', tet[2] + 1, ' ', tet[3] + 1, ' ',
                            mesh.tet_labels[t], '\n');
    }
    files.face = concat(mesh.faces.size(), " 1\n");
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const Triangle& tri = mesh.faces[f];
        files.face +=
            concat(f + 1, ' ', tri[0] + 1, ' ', tri[1] + 1, ' ', tri[2] + 1, ' ', face_tag(mesh.face_sides[f]), '\n');
    }
    return files;
}

TetMesh parse_tetgen(const TetgenFiles& files, const std::string& what)
{
    TetMesh mesh;
    const long long base = parse_nodes(files.node, what, mesh);
    read_name_comments(files.ele, "#", mesh.names);
    {
        const std::string clean = without_comments(files.ele, "#");
        ByteReader in(clean, what + ".ele");
        const std::size_t count = in.count("tetrahedra", 10);
        const long long corners = in.integer("the nodes per tet");
        if (corners != 4 && corners != 10) in.fail(concat(corners, " nodes per tet"), "write 4- or 10-node tets");
        const std::size_t attributes = in.count("region attributes", 0);
        in.skip_line();
        for (std::size_t t = 0; t < count; ++t) {
            in.integer("a tet number");
            std::array<std::uint32_t, 4> v{};
            for (std::uint32_t& vertex : v) vertex = node_of(in, base, mesh.vertices.size());
            for (long long extra = 4; extra < corners; ++extra) in.integer("a node number");
            const double region = attributes > 0 ? in.real("a region attribute") : 0.0;
            add_tet(mesh, v, checked_label(region, [&](double value) {
                        in.fail(concat("region attribute ", value, " is not a label 0..65535"),
                                "tag regions with labels");
                    }));
            in.skip_line();
        }
    }
    if (files.face.empty()) return mesh;
    const std::string clean = without_comments(files.face, "#");
    ByteReader in(clean, what + ".face");
    const std::size_t count = in.count("faces", 8);
    const std::size_t markers = in.count("boundary-marker flags", 0);
    in.skip_line();
    for (std::size_t f = 0; f < count; ++f) {
        in.integer("a face number");
        Triangle tri{};
        for (std::uint32_t& vertex : tri) vertex = node_of(in, base, mesh.vertices.size());
        const long long marker = markers > 0 ? in.integer("a boundary marker") : 0;
        mesh.faces.push_back(tri);
        mesh.face_sides.push_back(single_tag_pair(marker));
        in.skip_line();
    }
    return mesh;
}

} // namespace tissuemesh::io::detail

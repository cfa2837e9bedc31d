#include "io/detail/medit_format.h"

#include <map>

#include "core/error.h"
#include "io/detail/byte_reader.h"
#include "io/detail/msh_common.h"
#include "io/detail/text_records.h"

namespace tissuemesh::io::detail {

std::string format_medit(const TetMesh& mesh)
{
    std::string out = format_name_comments(mesh.names, "#");
    out += concat("MeshVersionFormatted 2\nDimension 3\nVertices\n", mesh.vertices.size(), "\n");
    for (const Vec3& v : mesh.vertices) {
        for (const double c : v) append_real(out, c), out += ' ';
        out += "0\n";
    }
    out += concat("Triangles\n", mesh.faces.size(), "\n");
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
        out += concat(mesh.faces[f][0] + 1, ' ', mesh.faces[f][1] + 1, ' ', mesh.faces[f][2] + 1, ' ',
                      face_tag(mesh.face_sides[f]), '\n');
    out += concat("Tetrahedra\n", mesh.tets.size(), "\n");
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        out += concat(mesh.tets[t][0] + 1, ' ', mesh.tets[t][1] + 1, ' ', mesh.tets[t][2] + 1, ' ', mesh.tets[t][3] + 1,
                      ' ', mesh.tet_labels[t], '\n');
    return out + "End\n";
}

TetMesh parse_medit(const std::string& text, const std::string& what)
{
    const std::string clean = without_comments(text, "#");
    ByteReader in(clean, what);
    TetMesh mesh;
    read_name_comments(text, "#", mesh.names);
    if (in.word() != "MeshVersionFormatted")
        in.fail("not a Medit .mesh file (no MeshVersionFormatted)", "check the file or its extension");
    in.integer("a version");
    // Numbers per record of the sections other tools write, after the count; 0: not a known section.
    const std::map<std::string, int, std::less<>> skipped{
        {"Edges", 3},   {"Quadrilaterals", 5},   {"Hexahedra", 9},
        {"Prisms", 7},  {"Corners", 1},          {"RequiredVertices", 1},
        {"Ridges", 1},  {"RequiredEdges", 1},    {"RequiredTriangles", 1},
        {"Normals", 3}, {"NormalAtVertices", 2}, {"Tangents", 3}};
    for (std::string_view keyword = in.word(); !keyword.empty() && keyword != "End"; keyword = in.word()) {
        if (keyword == "Dimension") {
            if (in.integer("a dimension") != 3) in.fail("the mesh is not 3-D", "write a 3-D tet mesh");
        } else if (keyword == "Vertices") {
            mesh.vertices.resize(in.count("vertices", 8));
            for (Vec3& v : mesh.vertices) {
                for (double& c : v) c = in.real("a coordinate");
                in.integer("a vertex reference");
            }
        } else if (keyword == "Triangles" || keyword == "Tetrahedra") {
            const bool tets = keyword == "Tetrahedra";
            const std::size_t count = in.count(tets ? "tetrahedra" : "triangles", tets ? 10 : 8);
            for (std::size_t e = 0; e < count; ++e) {
                std::array<std::uint32_t, 4> v{};
                for (int c = 0; c < (tets ? 4 : 3); ++c) {
                    const long long index = in.integer("a vertex index");
                    if (index < 1 || static_cast<unsigned long long>(index) > mesh.vertices.size())
                        throw InputError(concat(what, ": vertex index ", index, " is outside 1..", mesh.vertices.size(),
                                                " (at byte ", in.position(), "); the file is corrupt, write it again"));
                    v[static_cast<std::size_t>(c)] = static_cast<std::uint32_t>(index - 1);
                }
                const long long reference = in.integer("an element reference");
                if (tets) {
                    add_tet(mesh, v, checked_label(static_cast<double>(reference), [&](double value) {
                                in.fail(concat("tet reference ", value, " is not a label 0..65535"),
                                        "the file is corrupt");
                            }));
                } else {
                    mesh.faces.push_back({v[0], v[1], v[2]});
                    mesh.face_sides.push_back(single_tag_pair(reference));
                }
            }
        } else if (const auto found = skipped.find(keyword); found != skipped.end()) {
            const std::size_t count = in.count("records", 2 * static_cast<std::size_t>(found->second));
            for (std::size_t n = 0; n < count * static_cast<std::size_t>(found->second); ++n) in.real("a record value");
        } else {
            in.fail(concat("section \"", keyword.substr(0, 40), "\" is not supported"),
                    "save vertices, triangles and tetrahedra only");
        }
    }
    return mesh;
}

} // namespace tissuemesh::io::detail

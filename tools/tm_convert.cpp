// tm-convert: a tet mesh from any format we read to any we write, or a surface likewise; a tet mesh's
// interface faces can also be written as a surface.
#include <chrono>
#include <set>
#include <string>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/read_vtu.h"
#include "io/surface_io.h"
#include "io/tet_mesh_io.h"
#include "tools/mesh_format_options.h"
#include "tools/run_tool.h"

using namespace tissuemesh;

namespace {

/// The interface and boundary faces of a tet mesh as an interface complex (every vertex kept).
InterfaceComplex faces_of(const TetMesh& mesh)
{
    InterfaceComplex complex;
    complex.vertices = mesh.vertices;
    complex.triangles = mesh.faces;
    complex.sides = mesh.face_sides;
    complex.names = mesh.names;
    return complex;
}

} // namespace

int main(int argc, char** argv)
{
    std::string input, output;
    tools::MeshFormatFlags flags;
    bool surface_ascii = false;
    return tools::run_tool(
        argc, argv,
        {"tm-convert",
         "Converts a tet mesh between .msh (Gmsh 2.2 or 4.1, ASCII or binary: the input's variant is detected), "
         ".mesh (Medit), .node/.ele/.face (TetGen), .inp (Abaqus) and .vtu, keeping tissue labels, interface faces and "
         "tissue names where the formats hold them (.vtu to .vtu keeps every point and cell array: tm-solve's fields); "
         "or a surface between .ply, .vtp, .obj, "
         ".off and .stl. A tet mesh's interface faces can be written as a surface.",
         "Examples:\n  tm-convert -i head.msh -o head41.msh --msh-version 4.1 --binary\n"
         "  tm-convert -i head.msh -o head.vtu\n  tm-convert -i head.msh -o simnibs.msh --tissue-numbering simnibs "
         "--tissue-tags tags.json\n"
         "  tm-convert -i head.msh -o duneuro.msh --tissue-numbering duneuro   # and duneuro.con\n  tm-convert -i "
         "solution.vtu -o solution-zlib.vtu   # the fields, compressed\n  tm-convert -i head.msh -o head.node   # "
         "head.node, head.ele, head.face\n"
         "  tm-convert -i interfaces.ply -o interfaces.obj\n  tm-convert -i head.msh -o interfaces.ply\n"
         "  tm-convert -i interfaces.ply -o for-meshio.ply --ascii"},
        [&](CLI::App& app) {
            app.add_option("-i,--input", input, "Tet mesh or surface to read")->required();
            app.add_option("-o,--output", output, "File to write; the extension picks the format")->required();
            flags.add_to(app);
            app.add_flag("--ascii", surface_ascii,
                         "Surface output (.ply, .stl) as ASCII instead of binary: meshio reads "
                         "PLY labels only from ASCII");
        },
        [&](tools::ToolContext& context) {
            flags.check();
            const bool mesh_in = io::is_tet_mesh_path(input), mesh_out = io::is_tet_mesh_path(output);
            if (!mesh_in && mesh_out)
                throw InputError(concat(
                    input, ": a surface cannot become a tet mesh by conversion; tetrahedralize it with tm-tetra"));
            auto start = std::chrono::steady_clock::now();
            if (mesh_in) {
                // A .vtu's arrays (tm-solve's potential and fields) go on into a .vtu; other formats cannot hold them.
                const bool arrays = full_extension(input) == ".vtu" && full_extension(output) == ".vtu";
                io::VtuContent content;
                if (arrays) content = io::read_vtu(input);
                else content.mesh = io::read_tet_mesh(input);
                const TetMesh& mesh = content.mesh;
                const io::TetMeshWriteOptions options = flags.to_write_options(mesh);
                const double read_seconds = tools::seconds_since(start);
                start = std::chrono::steady_clock::now();
                if (arrays)
                    io::write_vtu(mesh, output, content.point_arrays, content.cell_arrays,
                                  options.vtu_compressed ? io::VtuEncoding::compressed : io::VtuEncoding::ascii);
                else if (mesh_out) io::write_tet_mesh(mesh, output, options);
                else io::write_surface(faces_of(mesh), output, io::SurfaceWriteOptions{.ascii = surface_ascii});
                const std::set<Label> tissues(mesh.tet_labels.begin(), mesh.tet_labels.end());
                context.log(concat(input, " -> ", output, ": ", mesh.vertices.size(), " nodes, ", mesh.tets.size(),
                                   " tets, ", mesh.faces.size(), " faces, ", tissues.size(), " tissues"));
                context.summary = {{"input", input},
                                   {"output", output},
                                   {"kind", mesh_out ? "tet mesh" : "faces of a tet mesh"},
                                   {"nodes", mesh.vertices.size()},
                                   {"tets", mesh.tets.size()},
                                   {"faces", mesh.faces.size()},
                                   {"tissues", tissues.size()},
                                   {"arrays", content.point_arrays.size() + content.cell_arrays.size()},
                                   {"seconds_read", read_seconds},
                                   {"seconds_write", tools::seconds_since(start)}};
                return;
            }
            if (flags.numbering != "labels")
                throw InputError(concat(output, ": --tissue-numbering is for tet meshes; a surface keeps its labels"));
            const InterfaceComplex complex = io::read_surface(input);
            const double read_seconds = tools::seconds_since(start);
            start = std::chrono::steady_clock::now();
            io::write_surface(complex, output, io::SurfaceWriteOptions{.ascii = surface_ascii});
            std::set<std::pair<Label, Label>> pairs;
            for (const LabelPair& pair : complex.sides) pairs.insert({pair.from, pair.to});
            context.log(concat(input, " -> ", output, ": ", complex.vertices.size(), " vertices, ",
                               complex.triangles.size(), " triangles, ", pairs.size(), " tissue pairs"));
            context.summary = {{"input", input},
                               {"output", output},
                               {"kind", "surface"},
                               {"vertices", complex.vertices.size()},
                               {"triangles", complex.triangles.size()},
                               {"tissue_pairs", pairs.size()},
                               {"seconds_read", read_seconds},
                               {"seconds_write", tools::seconds_since(start)}};
        });
}

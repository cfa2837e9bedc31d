// tm-improve: better-shaped tets in any of our meshes, tissues and interfaces kept.
#include "core/error.h"
#include "io/surface_io.h"
#include "io/tet_mesh_io.h"
#include "tools/improve_flags.h"
#include "tools/mesh_format_options.h"
#include "tools/report_json.h"
#include "tools/surface_step.h"
#include "tools/run_tool.h"
#include "volume/improve_mesh.h"
#include "volume/mark_interfaces.h"

using namespace tissuemesh;

int main(int argc, char** argv)
{
    tools::MeshFormatFlags format_flags;
    tools::ImproveFlags improve_flags;
    std::string input, output, surface, image;
    return tools::run_tool(
        argc, argv,
        {"tm-improve",
         "Improves the shape of a labelled tet mesh where its tets are worst (what tm-tetra and tm-refine run by "
         "default): "
         "worst tets first, nodes moved to raise the smallest sine of the dihedral angles around them, edge and "
         "multi-face removal (3-2, 4-4, 2-3 flips), and new nodes inside tissues and, for slivers between close "
         "interfaces, on the interfaces. No tet changes tissue; interface nodes slide on the interface surface (the "
         "complex given with --surface, else the mesh's own interface faces as read) and new ones lie on it; every "
         "step raises the worst quality where it acts. A mesh without interface faces (.vtu) gets them from its "
         "tissues.",
         "Examples:\n  tm-improve -i head.msh -o better.msh --surface remeshed.ply\n"
         "  tm-improve -i refined.msh -o better.msh --improve-target-deg 25 --json improve.json"},
        [&](CLI::App& app) {
            app.add_option("-i,--input", input, "Tet mesh (.msh, .mesh, .vtu, ...)")
                ->required()
                ->check(CLI::ExistingFile);
            app.add_option("-o,--output", output, "Improved tet mesh: .msh, .mesh, .vtu, .node, .inp")->required();
            app.add_option("--surface", surface,
                           "The interface complex the mesh was made from (.ply from tm-remesh): interface "
                           "nodes stay on it")
                ->check(CLI::ExistingFile);
            format_flags.add_to(app);
            improve_flags.add_to(app, false);
            app.add_option("--image", image,
                           "With --improve-keep-voxel-sides: the label image the mesh was made from (tm-prep's clean "
                           "image)");
        },
        [&](tools::ToolContext& context) {
            tools::require_image_with("--improve-keep-voxel-sides", improve_flags.keep_voxel_sides, image,
                                      "leave --improve-keep-voxel-sides out");
            TetMesh mesh = io::read_tet_mesh(input);
            if (mesh.faces.empty()) volume::mark_interfaces(mesh);
            const LabelImage voxels = improve_flags.read_voxel_image(image, context.memory);
            const volume::ImproveOptions options = improve_flags.to_options(&voxels);
            const volume::ImproveReport report = tools::with_source(input, [&] {
                if (surface.empty()) return volume::improve_mesh(mesh, options, context.progress);
                const InterfaceComplex complex = io::read_surface(surface);
                return volume::improve_mesh(mesh, complex, options, context.progress);
            });
            io::write_tet_mesh(mesh, output, format_flags.to_write_options());
            context.log(tools::improve_line(report));
            context.summary = report;
            context.summary["nodes"] = mesh.vertices.size();
            context.summary["tets"] = mesh.tets.size();
        });
}

// tm-check-mesh: is a tet mesh fit for FEM, and how well does it match the voxels?
#include <cstdio>

#include "core/error.h"
#include "io/read_label_image.h"
#include "io/tet_mesh_io.h"
#include "tools/run_tool.h"
#include "volume/check_mesh.h"

using namespace tissuemesh;

int main(int argc, char** argv)
{
    std::string input, image_path;
    return tools::run_tool(
        argc, argv,
        {"tm-check-mesh",
         "Checks a labelled tet mesh: conformity (faces shared by two tets on opposite sides), no inverted or flat tets "
         "(volume under 1e-9 of the longest edge cubed: four coplanar nodes), closed "
         "outer boundary, every interface face a tet face with the right tissues on both sides, per-tissue volumes and "
         "connected pieces, quality (dihedral angles, radius-edge ratio), and with --image the voxel agreement per tissue "
         "(Dice). Exit 0 when fit for FEM, 1 when defects were found, 2 when the input cannot be read.",
         "Examples:\n  tm-check-mesh head.msh\n  tm-check-mesh -i head.msh --image head.nii.gz --json check.json"},
        [&](CLI::App& app) {
            app.add_option("-i,--input,mesh", input, "Tet mesh (.msh 2.2 or .mesh)")->required();
            app.add_option("--image", image_path, "Label image to compare against (Dice per tissue)");
        },
        [&](tools::ToolContext& context) {
            const TetMesh mesh = io::read_tet_mesh(input);
            LabelImage image;
            if (!image_path.empty()) image = io::read_label_image(image_path);
            const volume::MeshCheckReport report = volume::check_mesh(mesh, image_path.empty() ? nullptr : &image, context.progress);
            std::printf("%s: %zu nodes, %zu tets, %zu interface faces\n", input.c_str(), report.nodes, report.tets, report.faces);
            std::printf("quality: min dihedral %.2f deg, max dihedral %.2f deg, radius-edge max %.2f mean %.3f\n",
                        report.quality.min_dihedral_deg, report.quality.max_dihedral_deg, report.quality.max_radius_edge_ratio,
                        report.quality.mean_radius_edge_ratio);
            std::printf("%-20s %10s %14s %10s %14s %8s\n", "tissue", "tets", "volume mm^3", "pieces", "voxels mm^3", "Dice");
            nlohmann::json tissues = nlohmann::json::object();
            for (const auto& [label, stats] : report.tissues) {
                const std::string name = mesh.names.count(label) ? mesh.names.at(label) : std::to_string(label);
                std::printf("%-20s %10zu %14.1f %10zu %14.1f %8.4f\n", name.c_str(), stats.tets, stats.volume_mm3, stats.components,
                            stats.voxel_volume_mm3, stats.dice);
                tissues[std::to_string(label)] = {{"name", name}, {"tets", stats.tets}, {"volume_mm3", stats.volume_mm3},
                                                  {"components", stats.components}, {"voxel_volume_mm3", stats.voxel_volume_mm3},
                                                  {"dice", stats.dice}};
            }
            for (const std::string& problem : report.problems) std::printf("defect: %s\n", problem.c_str());
            std::printf("%s\n", report.ok() ? "fit for FEM" : "NOT fit for FEM: see the defects above");
            context.summary = {{"ok", report.ok()}, {"nodes", report.nodes}, {"tets", report.tets}, {"faces", report.faces},
                               {"inverted_tets", report.inverted_tets}, {"flat_tets", report.flat_tets},
                               {"nonconforming_faces", report.nonconforming_faces},
                               {"open_boundary_edges", report.open_boundary_edges}, {"unused_nodes", report.unused_nodes},
                               {"missing_interface_faces", report.missing_interface_faces},
                               {"mislabelled_interface_faces", report.mislabelled_interface_faces},
                               {"unmarked_interfaces", report.unmarked_interfaces},
                               {"min_dihedral_deg", report.quality.min_dihedral_deg},
                               {"max_radius_edge_ratio", report.quality.max_radius_edge_ratio},
                               {"min_dihedral_histogram_10deg", report.quality.min_dihedral_histogram}, {"tissues", tissues}};
            context.exit_code = report.ok() ? 0 : 1;
        });
}

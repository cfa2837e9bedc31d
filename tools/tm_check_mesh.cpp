// tm-check-mesh: is a tet mesh fit for FEM, and how well does it match the voxels?
#include <algorithm>
#include <cstdio>

#include "core/error.h"
#include "io/read_label_image.h"
#include "io/surface_io.h"
#include "io/tet_mesh_io.h"
#include "tools/report_json.h"
#include "tools/run_tool.h"
#include "volume/check_mesh.h"
#include "volume/interface_distance.h"

using namespace tissuemesh;

int main(int argc, char** argv)
{
    std::string input, image_path, surface_path;
    return tools::run_tool(
        argc, argv,
        {"tm-check-mesh",
         "Checks a labelled tet mesh: conformity (faces shared by two tets on opposite sides), no inverted or flat "
         "tets "
         "(volume under 1e-9 of the longest edge cubed: four coplanar nodes), a closed "
         "outer boundary that does not pass through itself (tets overlapping), every interface face a tet face with "
         "the right tissues on both sides, per-tissue volumes and "
         "connected pieces, quality (dihedral angles, radius-edge ratio), and with --image the voxel agreement per "
         "tissue "
         "(Dice), and with --surface how far its interfaces lie from the complex it was made from. Exit 0 when fit for "
         "FEM, 1 when defects were found, 2 when the input cannot be read.",
         "Examples:\n  tm-check-mesh head.msh\n  tm-check-mesh -i head.msh --image head.nii.gz --json check.json\n"
         "  tm-check-mesh -i head.msh --image head.nii.gz --surface remeshed.ply"},
        [&](CLI::App& app) {
            app.add_option("-i,--input,mesh", input, "Tet mesh (.msh 2.2 or .mesh)")->required();
            app.add_option("--image", image_path, "Label image to compare against (Dice per tissue)");
            app.add_option("--surface", surface_path,
                           "Interface complex the mesh was made from (.ply): distance of the mesh's "
                           "interfaces to it (mm; in voxels with --image)")
                ->check(CLI::ExistingFile);
        },
        [&](tools::ToolContext& context) {
            const TetMesh mesh = io::read_tet_mesh(input);
            LabelImage image;
            if (!image_path.empty()) image = io::read_label_image(image_path);
            const volume::MeshCheckReport report =
                volume::check_mesh(mesh, image_path.empty() ? nullptr : &image, context.progress);
            std::printf("%s: %zu nodes, %zu tets, %zu interface faces\n", input.c_str(), report.nodes, report.tets,
                        report.faces);
            const auto& histogram = report.quality.min_dihedral_histogram;
            std::printf("quality: min dihedral %.2f deg (1st percentile of the tets' smallest %.2f deg; %zu tets under "
                        "10 deg, %zu "
                        "under 20), max dihedral %.2f deg, radius-edge max %.2f mean %.3f\n",
                        report.quality.min_dihedral_deg, report.quality.p1_min_dihedral_deg, histogram[0],
                        histogram[0] + histogram[1], report.quality.max_dihedral_deg,
                        report.quality.max_radius_edge_ratio, report.quality.mean_radius_edge_ratio);
            std::printf("%-20s %10s %14s %10s %14s %8s\n", "tissue", "tets", "volume mm^3", "pieces", "voxels mm^3",
                        "Dice");
            nlohmann::json tissues = nlohmann::json::object();
            for (const auto& [label, stats] : report.tissues) {
                const std::string name = mesh.names.count(label) ? mesh.names.at(label) : std::to_string(label);
                std::printf("%-20s %10zu %14.1f %10zu %14.1f %8.4f\n", name.c_str(), stats.tets, stats.volume_mm3,
                            stats.components, stats.voxel_volume_mm3, stats.dice);
                nlohmann::json& tissue = tissues[std::to_string(label)] = stats;
                tissue["name"] = name;
            }
            nlohmann::json distance_json;
            if (!surface_path.empty()) {
                const InterfaceComplex complex = io::read_surface(surface_path);
                const volume::InterfaceDistance d =
                    tools::with_source(input, [&] { return volume::interface_distance(mesh, complex); });
                // In voxels of the image's finest axis, when there is an image.
                const double voxel_mm =
                    image.empty() ? 0 : std::min({image.spacing_mm()[0], image.spacing_mm()[1], image.spacing_mm()[2]});
                std::printf("interfaces vs %s: nodes max %.4f mean %.4f mm, faces max %.4f mean %.4f mm",
                            surface_path.c_str(), d.max_node_mm, d.mean_node_mm, d.max_face_mm, d.mean_face_mm);
                if (voxel_mm > 0)
                    std::printf(" (nodes max %.4f mean %.4f, faces max %.4f mean %.4f voxels)",
                                d.max_node_mm / voxel_mm, d.mean_node_mm / voxel_mm, d.max_face_mm / voxel_mm,
                                d.mean_face_mm / voxel_mm);
                std::printf("%s\n",
                            d.unmatched_faces > 0
                                ? concat("; ", d.unmatched_faces, " faces of tissue pairs the surface lacks").c_str()
                                : "");
                distance_json = d;
                if (voxel_mm > 0) {
                    distance_json["voxel_mm"] = voxel_mm;
                    distance_json["max_node_voxels"] = d.max_node_mm / voxel_mm,
                    distance_json["mean_node_voxels"] = d.mean_node_mm / voxel_mm;
                    distance_json["max_face_voxels"] = d.max_face_mm / voxel_mm,
                    distance_json["mean_face_voxels"] = d.mean_face_mm / voxel_mm;
                }
            }
            for (const std::string& problem : report.problems) std::printf("defect: %s\n", problem.c_str());
            std::printf("%s\n", report.ok() ? "fit for FEM" : "NOT fit for FEM: see the defects above");
            context.summary = report;
            context.summary.update({{"ok", report.ok()},
                                    {"min_dihedral_deg", report.quality.min_dihedral_deg},
                                    {"max_radius_edge_ratio", report.quality.max_radius_edge_ratio},
                                    {"min_dihedral_histogram_10deg", report.quality.min_dihedral_histogram},
                                    {"tissues", tissues},
                                    {"p1_min_dihedral_deg", report.quality.p1_min_dihedral_deg},
                                    {"max_dihedral_deg", report.quality.max_dihedral_deg}});
            if (!distance_json.is_null()) context.summary["interface_distance"] = distance_json;
            context.exit_code = report.ok() ? 0 : 1;
        });
}

// tm-refine: adaptive refinement against the voxels (Mueller & Sachse), Delaunay-only or inside a tm-tetra mesh.
#include <cstdio>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/read_label_image.h"
#include "io/tet_mesh_io.h"
#include "tools/improve_flags.h"
#include "tools/mesh_format_options.h"
#include "tools/report_json.h"
#include "tools/run_tool.h"
#include "volume/refine.h"
#include "volume/refine_log.h"

using namespace tissuemesh;

namespace {

nlohmann::json summarize(const volume::RefineReport& report, const volume::RefineOptions& options, bool constrained)
{
    const volume::RefineIteration& first = report.iterations.front();
    const volume::RefineIteration& last = report.iterations.back();
    return {{"mode", constrained ? "constrained" : "delaunay"},
            {"placement", volume::placement_name(options.placement)},
            {"stop_reason", report.stop_reason},
            {"target_reached", report.target_reached},
            {"mesh_volume_mm3", report.mesh_volume_mm3},
            {"start_nodes", first.nodes},
            {"start_error_volume_mm3", first.total_error_volume_mm3},
            {"nodes", last.nodes},
            {"tets", last.tets},
            {"total_error_volume_mm3", last.total_error_volume_mm3},
            {"worst_quality_key", last.worst_quality_key},
            {"improved_error_volume_mm3", report.improved_error_volume_mm3 >= 0
                                              ? nlohmann::json(report.improved_error_volume_mm3)
                                              : nlohmann::json(nullptr)},
            {"refine_seconds", last.seconds},
            {"iterations", report.iterations}};
}

} // namespace

int main(int argc, char** argv)
{
    tools::MeshFormatFlags format_flags;
    tools::ImproveFlags improve_flags;
    std::string input, image_path, output, log_path, plot_path, placement = "material-centroid";
    volume::RefineOptions options;
    return tools::run_tool(
        argc, argv,
        {"tm-refine",
         "Refines a tet mesh until it matches a label image (Mueller & Sachse): every round assesses the tets against "
         "the voxels, places a node in each of the worst (by quality key: misclassified voxels + shape), and puts the "
         "nodes into the mesh; only new tets are assessed again. Without -i: Delaunay-only, starting from a coarse "
         "lattice over the image box, rebuilt by TetGen every round, each tet taking its majority tissue (the mesh "
         "covers the box; background tets carry label 0). With -i MESH (from tm-tetra): constrained, every interface "
         "face kept exactly and nodes added inside the tissues only, each in its Bowyer-Watson cavity (the tets "
         "around it whose circumsphere holds it, never across an interface; every other tet stays as it was), so the "
         "error volume stays what the interfaces give while shapes and resolution improve; at the end the tets are "
         "improved as tm-tetra improves them (interface nodes slide on the "
         "interfaces, so the error volume is measured again; no new nodes with --max-nodes; --improve-keep-interfaces "
         "--improve-insert-below-deg 0 keeps the last round's interfaces and nodes; --no-improve the last round's mesh "
         "as "
         "it is). Placements: centroid, incentre, longest-edge, material-half-edges, material-centroid (the first "
         "tissue change walking from edge midpoints or from the centroid towards the vertices).",
         "Examples:\n  tm-refine --image head.nii.gz -o head.msh --log refine.csv --plot refine.svg "
         "--target-error-percent 2\n"
         "  tm-refine -i head.msh --image head.nii.gz -o finer.msh --log refine.csv --max-nodes 200000\n"
         "  tm-refine --image head.nii.gz -o head.vtu --placement centroid --batch 0.1 --iterations 30"},
        [&](CLI::App& app) {
            app.add_option("-i,--input", input,
                           "Tet mesh to refine inside its interfaces (.msh, .mesh); none: Delaunay-only")
                ->check(CLI::ExistingFile);
            app.add_option("--image", image_path, "Label image the mesh must match")
                ->required()
                ->check(CLI::ExistingFile);
            app.add_option("-o,--output", output, "Refined mesh: .msh, .mesh, .vtu, .node, .inp")->required();
            format_flags.add_to(app);
            app.add_option("--log", log_path,
                           "Convergence log (CSV: iteration, nodes, tets, error volume, worst key, ...)");
            app.add_option("--plot", plot_path, "Error volume and worst key against nodes as an SVG plot");
            app.add_option("--placement", placement, "Where new nodes go")->capture_default_str();
            app.add_option("--batch", options.batch_fraction, "Share of tets refined per round, worst first")
                ->capture_default_str();
            app.add_option("--target-error-mm3", options.target_error_mm3, "Stop at this total error volume (mm^3)");
            app.add_option("--target-error-percent", options.target_error_percent, "Stop at this % of the mesh volume");
            app.add_option("--max-nodes", options.max_nodes, "Node budget")->check(CLI::NonNegativeNumber);
            app.add_option("--iterations", options.max_iterations, "Rounds at most")
                ->check(CLI::NonNegativeNumber)
                ->capture_default_str();
            app.add_option("--stalled-rounds", options.max_stalled_rounds,
                           "Delaunay-only: stop when the error volume has not "
                           "fallen over this many rounds (0: never)")
                ->check(CLI::NonNegativeNumber)
                ->capture_default_str();
            app.add_option("--initial-spacing-mm", options.initial_spacing_mm,
                           "Delaunay-only start lattice spacing (default: box / 4)");
            app.add_option("--min-node-distance-mm", options.min_node_distance_mm,
                           "Closest new node to another (default: half a voxel)");
            app.add_option("--error-weight", options.assess.error_weight, "Quality key weight of misclassified voxels")
                ->capture_default_str();
            app.add_option("--shape-weight", options.assess.shape_weight, "Quality key weight of the shape term")
                ->capture_default_str();
            app.add_flag("--rebuild-with-tetgen", options.tetgen_rebuild,
                         "With -i: each round rebuilds the whole mesh with TetGen from its nodes and interface faces "
                         "(slower, and the tets tm-tetra improved are made again), instead of inserting the new nodes "
                         "into the mesh as it is, each in its Bowyer-Watson cavity");
            improve_flags.options = options.improvement;
            improve_flags.add_to(app, true);
        },
        [&](tools::ToolContext& context) {
            format_flags.check();
            options.placement = volume::parse_placement(placement);
            options.improve = !improve_flags.off;
            const LabelImage image = io::read_label_image(image_path);
            options.improvement = improve_flags.to_options(&image); // --improve-keep-voxel-sides: this image
            TetMesh start;
            if (!input.empty()) start = io::read_tet_mesh(input);
            volume::RefineReport report;
            const TetMesh mesh =
                volume::refine(image, input.empty() ? nullptr : &start, options, context.progress, &report);
            io::write_tet_mesh(mesh, output, format_flags.to_write_options(mesh));
            if (!log_path.empty()) write_text_atomically(log_path, volume::refine_log_csv(report));
            if (!plot_path.empty())
                write_text_atomically(
                    plot_path,
                    volume::refine_plot_svg(
                        report, concat("tm-refine ", volume::placement_name(options.placement), ": ", image_path)));
            context.summary = summarize(report, options, !input.empty());
            // The written mesh: the last round's, improved (moves, flips and new nodes).
            context.summary["nodes"] = mesh.vertices.size(), context.summary["tets"] = mesh.tets.size();
            if (report.improved) {
                context.summary["improvement"] = report.improvement;
                context.log(tools::improve_line(report.improvement));
            }
            const volume::RefineIteration& last = report.iterations.back();
            std::printf("%s: %zu rounds, %zu -> %zu nodes, %zu tets, error volume %.1f -> %.1f mm^3 (%s)\n",
                        output.c_str(), report.iterations.size() - 1, report.iterations.front().nodes,
                        mesh.vertices.size(), mesh.tets.size(), report.iterations.front().total_error_volume_mm3,
                        report.improved_error_volume_mm3 >= 0 ? report.improved_error_volume_mm3
                                                              : last.total_error_volume_mm3,
                        report.stop_reason.c_str());
            if ((options.target_error_mm3 > 0 || options.target_error_percent > 0) && !report.target_reached)
                context.progress.warn("refine", concat("target error volume not reached (", report.stop_reason,
                                                       "); raise --iterations or --max-nodes"));
        });
}

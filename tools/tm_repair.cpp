// tm-repair: fixes what is cheap and unambiguous in an interface complex (coincident vertices, repeated,
// zero-area and flipped triangles) and moves crossing or touching surfaces apart locally, so that the
// output passes tm-check-surface; fails, writing nothing, when it cannot.
#include <chrono>
#include <optional>
#include <string>

#include "core/error.h"
#include "io/read_label_image.h"
#include "surface/repair.h"
#include "tools/report_json.h"
#include "tools/run_tool.h"
#include "tools/surface_step.h"

using namespace tissuemesh;

namespace {

nlohmann::json summarize(const surface::RepairReport& report)
{
    nlohmann::json actions = nlohmann::json::array();
    for (const surface::RepairAction& action : report.actions)
        actions.push_back({{"kind", surface::to_string(action.kind)},
                           {"location_mm", action.location_mm},
                           {"tissues", action.tissues},
                           {"description", action.description}});
    nlohmann::json summary = report;
    summary.update({{"changed", report.changed()}, {"actions", actions}});
    return summary;
}

} // namespace

int main(int argc, char** argv)
{
    std::string input, output, image_path;
    surface::RepairOptions options;
    return tools::run_tool(
        argc, argv,
        {"tm-repair",
         "Repairs an interface complex for tetrahedralization. Fixed where the fix is unambiguous: vertices at the "
         "same position are merged, repeated triangles dropped, zero-area triangles dropped or collapsed, triangles "
         "wound against their patch turned. Then triangles that cross, and with --gap-mm patches closer than the "
         "gap, are moved apart locally along their normals (a thin layer gets its thickness back; a patch folded "
         "through itself is smoothed), never changing the topology and never adding an intersection; with --image "
         "moved vertices stay near their tissues' voxels. Reports every change with tissues and location. The "
         "output passes tm-check-surface (it is checked); holes and a tissue touching itself are not repaired: "
         "exit 1, nothing written.",
         "Examples:\n  tm-repair -i edited.ply -o fixed.ply\n"
         "  tm-repair -i edited.ply -o fixed.ply --image head.nii.gz --gap-mm 0.1 --json repair.json\n"},
        [&](CLI::App& app) {
            app.add_option("-i,--input", input, "Interface complex (.ply, .vtp, .off, .stl)")->required();
            app.add_option("-o,--output", output, "Repaired interface complex (.ply or .vtp)")->required();
            app.add_option("--image", image_path, "The label image: moved vertices stay near their tissues' voxels");
            app.add_option("--gap-mm", options.gap_mm, "Push apart patches closer than this (0: only intersections)")
                ->capture_default_str();
            app.add_option("--max-rounds", options.max_rounds, "Rounds of local moves before giving up")
                ->capture_default_str();
        },
        [&](tools::ToolContext& ctx) {
            tools::require_complex_output(output);
            InterfaceComplex complex = io::read_surface(input);
            std::optional<LabelImage> image;
            if (!image_path.empty()) image = io::read_label_image(image_path);
            surface::RepairReport report;
            // repair() checks its own result (it throws unless the complex is fit), so no second check here.
            const auto start = std::chrono::steady_clock::now();
            report = surface::repair(complex, options, image ? &*image : nullptr, ctx.progress);
            const double seconds = tools::seconds_since(start);
            ctx.log(concat(report.triangles_before, " -> ", report.triangles_after, " triangles (",
                           format_mm(seconds, 2), " s): ", report.merged_vertices, " vertices merged, ",
                           report.removed_duplicates + report.removed_degenerate + report.collapsed_degenerate,
                           " triangles removed, ", report.flipped_triangles, " turned, ",
                           report.self_intersections_before + report.patch_intersections_before,
                           " intersecting pairs and ", report.near_contacts_before - report.near_contacts_after,
                           " near-contacts removed by moving ", report.moved_vertices, " vertices"));
            io::write_surface(complex, output);
            ctx.summary = summarize(report);
            ctx.summary["input"] = input;
            ctx.summary["output"] = output;
            if (!image_path.empty()) ctx.summary["image"] = image_path;
            ctx.summary["gap_mm"] = options.gap_mm;
            ctx.summary["seconds_repair"] = seconds;
        });
}

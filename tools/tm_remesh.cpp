// tm-remesh: well-shaped triangles of a target size on the same interfaces, junction curves kept.
#include <map>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/read_label_image.h"
#include "surface/remesh.h"
#include "tools/memory_limit.h"
#include "tools/report_json.h"
#include "tools/run_tool.h"
#include "tools/surface_step.h"
#include "tools/tissue_arguments.h"

using namespace tissuemesh;

namespace {

/// "1:0=3", "skull:scalp=2": tissue pair (labels or names) = edge length in mm.
std::map<std::pair<Label, Label>, double> parse_pair_lengths(const std::vector<std::string>& items,
                                                             const tools::TissueTable& tissues)
{
    std::map<std::pair<Label, Label>, double> lengths;
    for (const std::string& item : items) {
        const auto colon = item.find(':'), eq = item.find('=');
        double length = 0;
        if (colon != std::string::npos && eq != std::string::npos && colon < eq) {
            try {
                length = std::stod(item.substr(eq + 1));
            } catch (const std::exception&) {
            }
        }
        if (!(length > 0))
            throw InputError(concat("--edge-mm-pair ", item,
                                    ": expected TISSUE:TISSUE=MM with tissues as labels or "
                                    "names in the surface (e.g. --edge-mm-pair 1:0=4,skull:scalp=2)"));
        const std::string option = concat("--edge-mm-pair ", item);
        const Label a = tools::parse_tissue(std::string_view(item).substr(0, colon), tissues, option);
        const Label b = tools::parse_tissue(std::string_view(item).substr(colon + 1, eq - colon - 1), tissues, option);
        lengths[std::minmax(a, b)] = length;
    }
    return lengths;
}

} // namespace

int main(int argc, char** argv)
{
    bool check_input = false;
    std::string input, output, image;
    bool keep_voxel_sides = false;
    std::vector<std::string> pair_lengths;
    surface::RemeshOptions options;
    return tools::run_tool(
        argc, argv,
        {"tm-remesh",
         "Remeshes an interface complex towards edges of a target length (split long edges, collapse short ones, "
         "flip towards valence 6, relax vertices and project them back onto the input surface; junction curves "
         "are remeshed as curves). Every edit is checked, so the output passes tm-check-surface whenever the "
         "input does (both are checked; the .ply output carries the stamp of its passed check, so the next of these "
         "tools does not check it again): well-shaped triangles for tm-tetra.",
         "Examples:\n  tm-remesh -i coarse.ply -o remeshed.ply --edge-mm 2\n"
         "  tm-remesh -i coarse.ply -o remeshed.ply --edge-mm 3 --edge-mm-pair csf:skull=1.5,4:3=1.5\n"
         "  tm-remesh -i coarse.ply -o remeshed.ply --edge-mm 3 --keep-voxel-sides --image clean.nii.gz\n"},
        [&](CLI::App& app) {
            tools::add_step_files(app, input, output, check_input, "Remeshed interface complex (.ply or .vtp)");
            app.add_option("--edge-mm", options.target_edge_mm, "Target edge length")->capture_default_str();
            app.add_option("--edge-mm-pair", pair_lengths, "Target edge length per tissue pair, TISSUE:TISSUE=MM")
                ->delimiter(',');
            app.add_option("--iterations", options.iterations, "Rounds of split/collapse/flip/relax")
                ->check(CLI::NonNegativeNumber)
                ->capture_default_str();
            app.add_option("--min-angle-deg", options.min_angle_deg, "Smallest angle an edit may create")
                ->capture_default_str();
            app.add_option("--min-gap-mm", options.min_gap_mm, "Distance kept between patches")->capture_default_str();
            app.add_option(
                   "--min-sector-deg", options.min_sector_deg,
                   "Smallest angle an edit may leave between neighbouring triangles around an edge, on the side "
                   "of a tissue (it bounds the dihedral angles of tm-tetra's tets there; 0: no rule)")
                ->capture_default_str();
            app.add_option("--edge-per-thickness", options.edge_per_thickness,
                           "Edges at most this many times the thickness of the tissue layer they bound (measured "
                           "on the input along its normals), graded away from thin places; a layer thinner than "
                           "its edges is filled with flat tets (0: no such limit)")
                ->check(CLI::Range(0.0, 100.0))
                ->capture_default_str();
            app.add_flag("--keep-voxel-sides", keep_voxel_sides,
                         "No move or collapse carries the centre of a voxel of --image next to another tissue across "
                         "the surface, so the surfaces keep the voxels' tissues (the workflow's default: on the 1 mm "
                         "usc19-5 head the CSF's Dice against the voxels after tm-tetra 0.963 -> 0.989, for 12% more "
                         "tets and 12% more time here)");
            app.add_option("--image", image,
                           "With --keep-voxel-sides: the label image the surfaces come from (tm-prep's clean image)")
                ->check(CLI::ExistingFile);
            app.add_option("--min-edge-mm", options.min_edge_mm,
                           "With --edge-per-thickness: no edge target below this (0: a third of --edge-mm)")
                ->check(CLI::Range(0.0, 1e6))
                ->capture_default_str();
            app.add_option(
                   "--slabs", options.slabs,
                   "Slabs remeshed side by side (in parallel), then bands around their cuts; 0: one per 125 000 "
                   "triangles, at most 8; 64 at most (the result depends on it, not on the thread count)")
                ->check(CLI::Range(0, 64))
                ->capture_default_str();
        },
        [&](tools::ToolContext& ctx) {
            tools::require_complex_output(output);
            tools::require_image_with("--keep-voxel-sides", keep_voxel_sides, image, "leave --keep-voxel-sides out");
            // The complex first: an unfit one is refused before the image is read.
            tools::FitInput in = tools::read_fit_complex(input, check_input, ctx);
            LabelImage voxels;
            if (keep_voxel_sides) {
                // The labels (2 bytes a voxel) and a flag per voxel for the ones next to another label.
                voxels = io::read_label_image(
                    image, {.before_voxels = tools::image_memory_check(ctx.memory, image, 3,
                                                                       "crop it (tm-prep --crop-pad 2), or leave "
                                                                       "--image out")});
                options.voxel_image = &voxels;
            }
            InterfaceComplex& complex = in.complex;
            options.target_edge_mm_by_pair = parse_pair_lengths(pair_lengths, tools::tissue_table(complex, input));
            surface::RemeshReport report;
            const double seconds = tools::run_checked_step(
                complex, output, "remeshed", [&] { report = surface::remesh(complex, options, ctx.progress); });
            ctx.log(concat(report.triangles_before, " -> ", report.triangles_after, " triangles, smallest angle ",
                           format_mm(report.min_angle_before_deg, 3), " -> ", format_mm(report.min_angle_after_deg, 3),
                           " deg, smallest tissue sector ", format_mm(report.min_sector_before_deg, 3), " -> ",
                           format_mm(report.min_sector_after_deg, 3), " deg (", format_mm(seconds, 2), " s)"));
            tools::write_checked(complex, output);
            ctx.summary = report;
            ctx.summary.update({{"input", input},
                                {"input_checked", in.checked},
                                {"output", output},
                                {"max_distance_to_input_mm", report.max_distance_mm},
                                {"keep_voxel_sides", keep_voxel_sides},
                                {"image", image},
                                {"seconds_remesh", seconds}});
        });
}

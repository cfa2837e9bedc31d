// tm-smooth: smooths an interface complex (Taubin lambda|mu), every vertex held to the voxel evidence and
// every move checked, so the output is as fit for tetrahedralization as the input.
#include <string>

#include "core/error.h"
#include "io/read_label_image.h"
#include "surface/smooth.h"
#include "tools/report_json.h"
#include "tools/run_tool.h"
#include "tools/surface_step.h"

using namespace tissuemesh;

int main(int argc, char** argv)
{
    bool check_input = false;
    std::string input, output, image_path;
    surface::SmoothOptions options;
    return tools::run_tool(
        argc, argv,
        {"tm-smooth",
         "Smooths the interface complex written by tm-extract: vertices inside a patch move towards the mean of "
         "their neighbours, vertices on a junction curve along the curve, corners stay (Taubin lambda|mu, so "
         "volumes keep). No vertex leaves the voxels of its tissues by more than --max-depth-voxels, and no move "
         "may fold or cross a triangle or close the gap between layers: the output passes tm-check-surface "
         "whenever the input does (both are checked; the .ply output carries the stamp of its passed check, so the "
         "next of these tools does not check it again). Optionally (--fit-passes N, off by default) every patch vertex "
         "is then pulled onto the image's own sub-voxel estimate of its interface (the zero level of its two "
         "tissues' blurred indicators), which removes the voxel terraces Taubin's filter keeps on smooth shapes "
         "(spheres at 1 mm); on folded anatomy at 2 mm it lowered the Dice against the voxels.",
         "Examples:\n  tm-smooth -i head.ply --image head.nii.gz -o smooth.ply\n"
         "  tm-smooth -i head.ply --image head.nii.gz -o smooth.ply --iterations 20 --json smooth.json\n"},
        [&](CLI::App& app) {
            tools::add_step_files(app, input, output, check_input, "Smoothed interface complex (.ply or .vtp)");
            app.add_option("--image", image_path, "The label image the complex was extracted from")->required();
            app.add_option("--iterations", options.iterations, "Taubin step pairs")
                ->check(CLI::NonNegativeNumber)
                ->capture_default_str();
            app.add_option("--pairs-per-check", options.pairs_per_check,
                           "Taubin pairs run between two checks against the complex (0: all, checked once)")
                ->check(CLI::NonNegativeNumber)
                ->capture_default_str();
            app.add_option("--max-depth-voxels", options.max_depth_voxels,
                           "How far (voxels) a vertex may sit from the voxels of each of its tissues")
                ->capture_default_str();
            app.add_option("--fit-passes", options.fit_passes,
                           "Passes pulling vertices onto the image's interface (0: none)")
                ->check(CLI::NonNegativeNumber)
                ->capture_default_str();
            app.add_option("--fit-sigma-voxels", options.fit_sigma_voxels,
                           "Blur (voxels, in (0, 1]) of the tissue indicators the fit follows")
                ->capture_default_str();
            app.add_option("--min-gap-voxels", options.min_gap_voxels,
                           "Distance (voxels) kept between different patches that were not closer")
                ->capture_default_str();
        },
        [&](tools::ToolContext& ctx) {
            tools::require_complex_output(output);
            tools::FitInput in = tools::read_fit_complex(input, check_input, ctx);
            InterfaceComplex& complex = in.complex;
            const LabelImage image = io::read_label_image(image_path);
            surface::SmoothReport report;
            const double seconds = tools::run_checked_step(
                complex, output, "smoothed", [&] { report = surface::smooth(complex, image, options, ctx.progress); });
            ctx.log(concat(report.moves, " moves in ", report.iterations, " iterations (", format_mm(seconds, 2),
                           " s); mean displacement ", format_mm(report.mean_displacement_mm, 3), " mm"));
            tools::write_checked(complex, output);
            ctx.summary = report;
            ctx.summary.update({{"input", input},
                                {"input_checked", in.checked},
                                {"image", image_path},
                                {"output", output},
                                {"triangles", complex.triangle_count()},
                                {"seconds_smooth", seconds}});
        });
}

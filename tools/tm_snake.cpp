// tm-snake: active contours on a label or grey-level image: closed surfaces that settle on tissue boundaries,
// nested snakes as one interface complex fit for tetrahedralization.
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/read_grey_image.h"
#include "io/read_label_image.h"
#include "io/surface_io.h"
#include "surface/check_complex.h"
#include "surface/snake.h"
#include "tools/report_json.h"
#include "tools/run_tool.h"
#include "tools/surface_step.h"
#include "tools/tissue_arguments.h"

using namespace tissuemesh;

namespace {

struct Start {
    std::string init = "auto";
    std::vector<double> centre_mm, radii_mm;
    double scale = 1.15;
};

InterfaceComplex start_surface(const Start& start, const std::vector<surface::SnakeTarget>& targets, double edge_mm)
{
    if (start.init == "auto") return surface::bounding_ellipsoids(targets, start.scale, edge_mm);
    if (start.init == "sphere" || start.init == "ellipsoid") {
        const bool sphere = start.init == "sphere";
        if (targets.size() != 1 || start.centre_mm.size() != 3 || start.radii_mm.size() != (sphere ? 1u : 3u))
            throw InputError(concat("--init ", start.init, " needs one snake, --centre X,Y,Z and ",
                                    sphere ? "--radius R" : "--radii A,B,C",
                                    " (mm); nested snakes start from "
                                    "--init auto or a surface file"));
        const Vec3 radii = sphere ? Vec3{start.radii_mm[0], start.radii_mm[0], start.radii_mm[0]}
                                  : Vec3{start.radii_mm[0], start.radii_mm[1], start.radii_mm[2]};
        return surface::ellipsoid_surface({start.centre_mm[0], start.centre_mm[1], start.centre_mm[2]}, radii, edge_mm,
                                          targets.front().pair);
    }
    InterfaceComplex complex = io::read_surface(start.init);
    surface::label_start_surface(complex, targets, start.init);
    return complex;
}

} // namespace

int main(int argc, char** argv)
{
    std::string input, output, names_json, tissue;
    std::vector<std::string> nested;
    bool grey = false, dark_inside = false;
    double iso = 0;
    std::optional<double> sigma_mm;
    Start start;
    surface::SnakeOptions options;
    return tools::run_tool(
        argc, argv,
        {"tm-snake",
         "Active contours: closed triangle surfaces move under tension, rigidity and an image force until they "
         "settle on a boundary. Label images: the boundary of a tissue and everything it encloses (--tissue), or "
         "of several nested tissues at once (--nested, outermost first), from the tissue indicator smoothed by a "
         "Gaussian. Grey images (--grey: CT, MRI values in NIfTI-1, NRRD, MetaImage or Inrimage): the iso-surface at "
         "--iso. The surfaces are refined and "
         "coarsened as they move, never intersect, and nested ones keep --min-separation-voxels apart; the output "
         "is one interface complex fit for tm-tetra.",
         "Examples:\n  tm-snake -i head.nii.gz --labels head.json --tissue brain -o brain.ply\n"
         "  tm-snake -i head.nii.gz --nested scalp,skull,csf,brain -o head.ply --json snake.json\n"
         "  tm-snake -i skull_2.9.inr --grey --iso 2.9 --tension 0.5 --rigidity 0.2 --max-step-voxels 0.25 -o "
         "skull.ply\n"
         "  tm-snake -i head.nii.gz --tissue 4 --init sphere --centre 0,0,10 --radius 60 -o brain.vtp\n"},
        [&](CLI::App& app) {
            app.add_option(
                   "-i,--input", input,
                   "Label image, or grey image (.nii, .nii.gz, .nrrd, .nhdr, .mha, .mhd, .inr, .inr.gz) with --grey")
                ->required();
            app.add_option("-o,--output", output, "Interface complex (.ply or .vtp)")->required();
            tools::add_labels_option(app, names_json);
            app.add_option("--tissue", tissue, "One snake: this tissue (name or label) and what it encloses");
            app.add_option("--nested", nested, "Nested snakes, outermost first (names or labels)")->delimiter(',');
            app.add_flag("--grey", grey, "The input holds grey values; the snake seeks the --iso surface");
            app.add_option("--iso", iso, "Grey value of the boundary (with --grey)");
            app.add_flag("--dark-inside", dark_inside, "With --grey: inside is below the iso value (default above)");
            app.add_option("--sigma-mm", sigma_mm, "Gaussian smoothing of the field (default 1 voxel; grey: 0)");
            app.add_option("--init", start.init,
                           "auto (ellipsoids around each region), sphere, ellipsoid or a "
                           "surface file")
                ->capture_default_str();
            app.add_option("--centre", start.centre_mm, "Start centre X,Y,Z (mm)")->delimiter(',');
            app.add_option("--radius", start.radii_mm, "Start sphere radius (mm)");
            app.add_option("--radii", start.radii_mm, "Start ellipsoid semi-axes A,B,C (mm)")->delimiter(',');
            app.add_option("--start-scale", start.scale, "--init auto: semi-axes over the region's half extents")
                ->capture_default_str();
            app.add_option("--image-weight", options.image_weight,
                           "Fraction of the distance to the boundary moved "
                           "per iteration")
                ->capture_default_str();
            app.add_option("--tension", options.tension, "Umbrella Laplacian weight")->capture_default_str();
            app.add_option("--rigidity", options.rigidity, "Bi-Laplacian weight")->capture_default_str();
            app.add_option("--balloon-voxels", options.balloon_voxels,
                           "Outward motion per iteration (negative "
                           "deflates)")
                ->capture_default_str();
            app.add_option("--max-step-voxels", options.max_step_voxels, "Largest motion per iteration")
                ->capture_default_str();
            app.add_option("--edge-mm", options.target_edge_mm, "Target edge length (0: 2 voxels)")
                ->capture_default_str();
            app.add_option("--max-chord-error-mm", options.max_chord_error_mm,
                           "Curvature-adapted edges: chord error bound (0: off)")
                ->capture_default_str();
            app.add_option("--resolution-every", options.resolution_every, "Split/collapse/flip every N iterations")
                ->capture_default_str();
            app.add_option("--min-separation-voxels", options.min_separation_voxels, "Gap kept between snakes")
                ->capture_default_str();
            app.add_option("--iterations", options.max_iterations, "Iteration cap")->capture_default_str();
            app.add_option("--tolerance-voxels", options.tolerance_voxels, "Converged below this largest motion")
                ->capture_default_str();
        },
        [&](tools::ToolContext& ctx) {
            tools::require_complex_output(output);
            if (int{grey} + int{!tissue.empty()} + int{!nested.empty()} != 1)
                throw InputError("choose one of --tissue T, --nested T1,T2,... (label images) or --grey --iso V");
            std::vector<surface::SnakeTarget> targets;
            LabelImage image;
            if (grey) {
                const io::GreyImage grey_image = io::read_grey_image(input);
                targets.push_back({{1, 0},
                                   surface::grey_potential(grey_image.grid, grey_image.values, iso,
                                                           sigma_mm.value_or(0.0), !dark_inside)});
                image = grey_image.grid;
                image.names() = {{0, "outside"}, {1, "inside"}};
            } else {
                image = io::read_label_image(input, {.names_json = names_json});
                const Vec3& s = image.spacing_mm();
                const double sigma = sigma_mm.value_or(std::min({s[0], s[1], s[2]}));
                const tools::TissueTable table = tools::tissue_table(image, input);
                std::vector<Label> tissues;
                for (const std::string& t : nested.empty() ? std::vector<std::string>{tissue} : nested)
                    tissues.push_back(tools::parse_tissue(t, table, nested.empty() ? "--tissue" : "--nested"));
                targets = surface::nested_label_targets(image, tissues, sigma);
            }
            const double voxel = targets.front().field.smallest_spacing_mm();
            InterfaceComplex complex =
                start_surface(start, targets, options.target_edge_mm > 0 ? options.target_edge_mm : 2 * voxel);
            complex.names = image.names();
            surface::SnakeReport report;
            const double seconds = tools::run_checked_step(complex, output, "snakes", [&] {
                report = surface::evolve_snakes(complex, targets, options, ctx.progress);
            });
            ctx.log(concat(targets.size(), " snake(s): ", report.iterations, " iterations, ",
                           report.converged ? "converged" : "stopped at the cap", ", ", report.triangles,
                           " triangles (", format_mm(seconds, 2), " s)"));
            tools::write_checked(complex, output);
            ctx.summary = report;
            ctx.summary.update({{"input", input},
                                {"output", output},
                                {"snakes", targets.size()},
                                {"max_iterations", options.max_iterations},
                                {"tolerance_mm", options.tolerance_voxels * voxel},
                                {"seconds_snake", seconds}});
        });
}

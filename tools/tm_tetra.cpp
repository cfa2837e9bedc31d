// tm-tetra: interface complex -> labelled tetrahedral mesh (TetGen), every interface kept.
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <sstream>

#include "core/error.h"
#include "io/surface_io.h"
#include "io/tet_mesh_io.h"
#include "tools/improve_flags.h"
#include "tools/mesh_format_options.h"
#include "tools/report_json.h"
#include "tools/surface_step.h"
#include "tools/run_tool.h"
#include "tools/tissue_arguments.h"
#include "volume/tetrahedralize.h"

using namespace tissuemesh;

namespace {

/// Parses "8" (every tissue) or "scalp=8,4=2.5" (per tissue, by name or label) into the options.
void parse_sizes(const std::string& text, const tools::TissueTable& tissues, const std::string& option, bool as_edge_mm,
                 volume::TetrahedralizeOptions& options)
{
    // A regular tet with edge L has volume L^3 / (6 sqrt 2).
    auto to_volume = [&](double value) { return as_edge_mm ? value * value * value / (6.0 * std::sqrt(2.0)) : value; };
    std::stringstream items(text);
    for (std::string item; std::getline(items, item, ',');) {
        const auto equals = item.find('=');
        const std::string number = equals == std::string::npos ? item : item.substr(equals + 1);
        char* end = nullptr;
        const double value = std::strtod(number.c_str(), &end);
        if (number.empty() || *end != '\0' || !(value > 0))
            throw InputError(concat("size \"", item, "\" is not a positive number; write e.g. 8 or scalp=8,brain=4"));
        if (equals == std::string::npos) options.max_volume_mm3 = to_volume(value);
        else
            options
                .max_volume_per_tissue_mm3[tools::parse_tissue_setting(item, tissues, option, "scalp=8,4=2.5").tissue] =
                to_volume(value);
    }
}

/// A tissue's extent, from the interfaces around it.
struct TissueExtent {
    double volume_mm3 = 0; ///< enclosed volume (divergence theorem over the oriented interfaces)
    double area_mm2 = 0;   ///< area of its interfaces
    double triangles = 0;  ///< interface triangles around it
};

/// Extent per tissue, the background left out (its volume is negative).
std::map<Label, TissueExtent> tissue_extents(const InterfaceComplex& complex)
{
    std::map<Label, TissueExtent> extents;
    for (std::size_t t = 0; t < complex.triangle_count(); ++t) {
        const Vec3& a = complex.vertices[complex.triangles[t][0]];
        const Vec3& b = complex.vertices[complex.triangles[t][1]];
        const Vec3& c = complex.vertices[complex.triangles[t][2]];
        const double six_v = dot(a, cross(b, c)), area = 0.5 * norm(cross(b - a, c - a));
        for (const auto& [label, sign] :
             {std::pair{complex.sides[t].from, 1.0}, std::pair{complex.sides[t].to, -1.0}}) {
            TissueExtent& extent = extents[label];
            extent.volume_mm3 += sign * six_v / 6; // the normal points out of `from`
            extent.area_mm2 += area;
            extent.triangles += 1;
        }
    }
    extents.erase(complex.background);
    return extents;
}

// Memory of a TetGen run (the child process's peak), fitted to runs on the thin phantom and spheres4 at 3 mm with
// and without a volume bound, and matching the 2 mm sphere head and 1 mm usc19-5 head of bench/HISTORY.md within
// 2% (docs/robustness.md): about bytes_per_triangle per interface triangle (TetGen's subfaces, segments and its
// constrained recovery) and bytes_per_tet per tet. TetGen made 2.3-3.4 tets per triangle under the quality
// bounds alone, and about 2.1 tets per bound's volume of tissue where a volume bound acts. With the interfaces
// kept as they are (no Steiner point on them), the bound acts only farther than about a triangle's edge from
// them: a 10 mm box of 12 triangles stays 6 tets whatever the bound.
constexpr double tets_per_triangle = 3.4;
constexpr double tets_per_bound = 2.5;
constexpr double bytes_per_triangle = 1900;
constexpr double bytes_per_tet = 165;

/// About how many tets TetGen will make.
double expected_tets(const InterfaceComplex& complex, const volume::TetrahedralizeOptions& options)
{
    double bounded = 0;
    for (const auto& [label, extent] : tissue_extents(complex)) {
        const auto own = options.max_volume_per_tissue_mm3.find(label);
        const double bound = own != options.max_volume_per_tissue_mm3.end() ? own->second : options.max_volume_mm3;
        if (!(bound > 0) || !(extent.volume_mm3 > 0)) continue;
        // The edge of an equilateral triangle of the tissue's mean triangle area.
        const double edge_mm = std::sqrt(4 / std::sqrt(3.0) * extent.area_mm2 / extent.triangles);
        const double refinable =
            options.preserve_interfaces ? extent.volume_mm3 - extent.area_mm2 * edge_mm : extent.volume_mm3;
        bounded += tets_per_bound * std::max(refinable, 0.0) / bound;
    }
    return std::max(tets_per_triangle * static_cast<double>(complex.triangle_count()), bounded);
}

/// Refuses a run that would need more memory than --max-memory allows, before TetGen starts.
void check_memory(const tools::ToolContext& context, const std::string& input, const InterfaceComplex& complex,
                  const volume::TetrahedralizeOptions& options)
{
    const double tets = expected_tets(complex, options), triangles = static_cast<double>(complex.triangle_count());
    tools::require_memory(
        context.memory, input, tets * bytes_per_tet + bytes_per_triangle * triangles,
        concat(tools::format_count(triangles), " triangles x ", tools::format_bytes(bytes_per_triangle), " and about ",
               tools::format_count(tets), " tets x ", tools::format_bytes(bytes_per_tet)),
        "give larger tets (--max-volume, --max-edge-mm) or fewer triangles (tm-decimate, tm-remesh --edge-mm)");
}

} // namespace

int main(int argc, char** argv)
{
    tools::MeshFormatFlags format_flags;
    tools::ImproveFlags improve_flags;
    std::string input, output, max_volume, max_edge, image;
    volume::TetrahedralizeOptions options;
    bool allow_steiner = false, no_quality = false, drop_cavities = false;
    return tools::run_tool(
        argc, argv,
        {"tm-tetra",
         "Tetrahedralizes an interface complex (from tm-extract and the surface tools) with TetGen's constrained "
         "Delaunay mesher, then improves the tets (tm-improve's improver: slivers and flat tets next to the interfaces "
         "smoothed, flipped or split; interface nodes stay on the input surface). Every interface is kept; each tet's "
         "tissue comes from the interfaces around it. The output format follows the extension: .msh (Gmsh 2.2, "
         "SimNIBS/DUNEuro), .mesh (Medit), .vtu (ParaView).",
         "Examples:\n  tm-tetra -i head.ply -o head.msh\n  tm-tetra -i head.ply -o head.msh --max-volume 8,brain=2\n"
         "  tm-tetra -i head.ply -o head.vtu --max-edge-mm scalp=4,brain=2 --radius-edge 1.5"},
        [&](CLI::App& app) {
            app.add_option("-i,--input", input, "Interface complex (.ply from tm-extract)")
                ->required()
                ->check(CLI::ExistingFile);
            app.add_option("-o,--output", output, "Tet mesh: .msh, .mesh, .vtu, .node, .inp")->required();
            format_flags.add_to(app);
            app.add_option("--max-volume", max_volume, "Largest tet volume in mm^3: a number, or tissue=value,...");
            app.add_option("--max-edge-mm", max_edge, "Like --max-volume, as the edge length in mm of a regular tet");
            app.add_option("--radius-edge", options.max_radius_edge_ratio,
                           "Bound on circumradius / shortest edge (>= 1)")
                ->capture_default_str();
            app.add_option("--min-dihedral-deg", options.min_dihedral_deg, "Bound on the smallest dihedral angle")
                ->capture_default_str();
            app.add_option("--optimise", options.optimisation_level, "Mesh optimisation level 0..10")
                ->check(CLI::Range(0, 10))
                ->capture_default_str();
            app.add_flag("--no-quality", no_quality, "Do not refine for the radius-edge and dihedral bounds");
            app.add_flag("--allow-steiner", allow_steiner,
                         "Let TetGen split interface triangles for the bounds (it still "
                         "misses them next to small input angles); interfaces kept "
                         "as surfaces, not as the input triangles");
            app.add_flag("--drop-cavities", drop_cavities, "Do not mesh background enclosed by tissues");
            app.add_flag("--layer-points", options.layer_points,
                         "Give TetGen nodes inside the tissue layers, about an edge off the interface vertices, so "
                         "fewer tets span a layer from side to side (fewer slivers for the improver)");
            improve_flags.add_to(app, true);
            app.add_option("--image", image,
                           "With --improve-keep-voxel-sides: the label image the surfaces come from (tm-prep's clean "
                           "image)");
        },
        [&](tools::ToolContext& context) {
            format_flags.check();
            tools::require_image_with("--improve-keep-voxel-sides", improve_flags.keep_voxel_sides, image,
                                      "leave --improve-keep-voxel-sides out");
            const InterfaceComplex complex = io::read_surface(input);
            options.preserve_interfaces = !allow_steiner;
            options.improve_quality = !no_quality;
            options.mesh_background_cavities = !drop_cavities;
            options.improve = !improve_flags.off;
            const LabelImage voxels = improve_flags.read_voxel_image(image, context.memory);
            options.improvement = improve_flags.to_options(&voxels);
            const tools::TissueTable tissues = tools::tissue_table(complex, input);
            if (!max_volume.empty()) parse_sizes(max_volume, tissues, "--max-volume", false, options);
            if (!max_edge.empty()) parse_sizes(max_edge, tissues, "--max-edge-mm", true, options);
            check_memory(context, input, complex, options);
            volume::TetrahedralizeReport report;
            const TetMesh mesh = tools::with_source(
                input, [&] { return volume::tetrahedralize(complex, options, context.progress, &report); });
            io::write_tet_mesh(mesh, output, format_flags.to_write_options(mesh));
            context.log(concat(report.input_triangles, " triangles -> ", report.tets, " tets, ", report.nodes,
                               " nodes (", report.steiner_points, " added",
                               options.layer_points ? concat(", ", report.layer_points, " inside the layers") : "",
                               ") in ", format_mm(report.seconds, 2), " s; min dihedral ",
                               format_mm(report.min_dihedral_deg, 1), " deg, max radius-edge ",
                               format_mm(report.max_radius_edge_ratio, 2)));
            if (report.improved) context.log(tools::improve_line(report.improvement));
            if (report.split_interface_triangles > 0 && options.preserve_interfaces)
                context.progress.warn("tm-tetra",
                                      concat("TetGen split ", report.split_interface_triangles,
                                             " interface triangles "
                                             "despite -Y (the interfaces are unchanged: the parts cover them)"));
            if (report.tets_over_volume_bound > 0)
                context.progress.warn("tm-tetra",
                                      concat(report.tets_over_volume_bound,
                                             " tets exceed their volume bound (interface "
                                             "triangles too large for it: remesh finer, or --allow-steiner)"));
            context.summary = report;
            context.summary.update({{"tetgen_switches", report.switches}, {"tetrahedralize_seconds", report.seconds}});
            if (report.improved) context.summary["improvement"] = report.improvement;
        });
}

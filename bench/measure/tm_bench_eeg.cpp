// tm-bench-eeg: EEG forward accuracy of any tet mesh of the 4-shell sphere head (phantom spheres4:
// brain, CSF, skull, scalp to radii 78/80/86/92 mm). Radial and tangential dipoles at chosen
// eccentricities of the brain are solved on the mesh and compared on its outer surface nodes with the
// analytic series (fem/sphere_series.h): RDM on the 0..2 scale and MAG, both average-referenced. The same
// measure for every mesher (our pipeline, CGAL), so meshes can be compared at matched accuracy. The dipoles lie
// on the z axis or, with --directions N, also on N - 1 more axes spread evenly over the sphere (a golden-angle
// spiral): one axis draws only the few tets around its sources, and partial integration's error is such a draw.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include "bench/measure/spheres4_head.h"
#include "core/error.h"
#include "fem/conductivities.h"
#include "fem/outer_boundary.h"
#include "fem/solve_potential.h"
#include "fem/sphere_series.h"
#include "io/read_label_image.h"
#include "io/tet_mesh_io.h"
#include "tools/dipole_model.h"
#include "tools/run_tool.h"

using namespace tissuemesh;

namespace {

/// The z axis, then n - 1 unit vectors on a golden-angle spiral from pole to pole (evenly spread).
std::vector<Vec3> spread_axes(std::size_t n)
{
    std::vector<Vec3> axes{{0, 0, 1}};
    const double golden = std::numbers::pi * (3 - std::sqrt(5.0));
    for (std::size_t k = 0; k + 1 < n; ++k) {
        const double z = 1 - (2.0 * static_cast<double>(k) + 1) / static_cast<double>(n - 1);
        const double r = std::sqrt(1 - z * z), phi = golden * static_cast<double>(k);
        axes.push_back({r * std::cos(phi), r * std::sin(phi), z});
    }
    return axes;
}

} // namespace

int main(int argc, char** argv)
{
    std::string input, labels;
    std::vector<double> eccentricities{0.5, 0.9};
    bool partial_integration = false;
    std::string model_name = "subtraction";
    std::size_t directions = 1;
    return tools::run_tool(
        argc, argv,
        {"tm-bench-eeg",
         "EEG forward accuracy of a tet mesh of the 4-shell sphere head (tm-phantom spheres4; its tissues named "
         "brain, csf, skull, scalp, conductivities 0.33/1.79/0.01/0.43 S/m): radial and tangential dipoles "
         "(1e-8 A*m) on the z axis at the given eccentricities of the 78 mm brain, solved by AMG-CG to 1e-10 and "
         "compared with the analytic series on the mesh's outer surface nodes (with --directions, on more axes "
         "spread over the sphere too). RDM (0..2) and MAG, average reference; per dipole, per eccentricity and the "
         "worst over the dipoles in --json.",
         "Example:\n  tm-bench-eeg -i cgal.msh --labels spheres4.labels.json --eccentricities 0.5,0.9 --json eeg.json\n"
         "  tm-bench-eeg -i ours.msh --dipole-model venant --directions 13 --eccentricities 0.2,0.5,0.8,0.9,0.95"},
        [&](CLI::App& app) {
            app.add_option("-i,--input", input, "Tet mesh of the spheres4 phantom")
                ->required()
                ->check(CLI::ExistingFile);
            app.add_option("--labels", labels,
                           "Tissue names by label (JSON, as tm-phantom writes), for a mesh that has none")
                ->check(CLI::ExistingFile);
            app.add_option("--eccentricities", eccentricities, "Dipole depths as fractions of the brain radius")
                ->delimiter(',')
                ->check(CLI::Range(0.0, 0.99))
                ->capture_default_str();
            app.add_option("--dipole-model", model_name, "Source model: venant, subtraction or partial-integration")
                ->check(CLI::IsMember(tools::dipole_model_names))
                ->capture_default_str();
            app.add_flag("--partial-integration", partial_integration, "Same as --dipole-model partial-integration");
            app.add_option("--directions", directions,
                           "Axes the dipoles lie on: the z axis and N - 1 more spread evenly over the sphere")
                ->check(CLI::Range(1, 1000))
                ->capture_default_str();
        },
        [&](tools::ToolContext& context) {
            TetMesh mesh = io::read_tet_mesh(input);
            if (!labels.empty()) mesh.names = io::read_tissue_names(labels);
            const fem::Conductivities sigma = tools::with_source(
                input, [&] { return fem::resolve_conductivities(mesh, bench::spheres4_conductivities, false); });
            const std::vector<std::uint32_t> surface = fem::outer_boundary(mesh).nodes;
            if (partial_integration) model_name = "partial-integration";
            const fem::DipoleModel model = tools::dipole_model_named(model_name);
            const std::vector<Vec3> axes = spread_axes(directions);
            nlohmann::json dipoles = nlohmann::json::array();
            std::map<double, std::array<double, 3>> per_eccentricity; // smallest RDM, largest RDM, worst |MAG - 1|
            double worst_rdm = 0, worst_mag = 0, seconds = 0;
            for (const double eccentricity : eccentricities)
                for (std::size_t axis = 0; axis < axes.size(); ++axis)
                    for (const bool radial : {true, false}) {
                        const Vec3& d = axes[axis];
                        const Vec3 position = eccentricity * bench::spheres4_series.radii_mm[0] * d;
                        // Tangential: the x axis made perpendicular to d (the x axis itself for the z axis), else y.
                        const Vec3 across = std::abs(d[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
                        const Vec3 tangent = across - dot(across, d) * d;
                        const Vec3 moment = 1e-8 * (radial ? d : (1.0 / norm(tangent)) * tangent);
                        fem::PotentialProblem problem;
                        problem.dipoles = {{position, moment}};
                        problem.dipole_model = model;
                        const auto start = std::chrono::steady_clock::now();
                        const std::vector<double> phi =
                            fem::solve_potential(mesh, sigma, problem, {.relative_tolerance = 1e-10}, context.progress);
                        seconds += tools::seconds_since(start);
                        std::vector<double> numeric;
                        std::vector<Vec3> points;
                        for (const std::uint32_t node : surface)
                            numeric.push_back(phi[node]), points.push_back(mesh.vertices[node]);
                        const fem::Agreement a = fem::compare_potentials(
                            numeric, fem::sphere_surface_potentials(bench::spheres4_series, position, moment, points));
                        context.log(concat(radial ? "radial" : "tangential", " dipole at eccentricity ", eccentricity,
                                           " on axis ", axis, ": RDM ", a.rdm, ", MAG ", a.mag));
                        dipoles.push_back({{"eccentricity", eccentricity},
                                           {"axis", axis},
                                           {"position_mm", position},
                                           {"radial", radial},
                                           {"rdm", a.rdm},
                                           {"mag", a.mag}});
                        worst_rdm = std::max(worst_rdm, a.rdm);
                        worst_mag = std::max(worst_mag, std::abs(a.mag - 1));
                        auto& cell = per_eccentricity.try_emplace(eccentricity, std::array<double, 3>{a.rdm, a.rdm, 0})
                                         .first->second;
                        cell = {std::min(cell[0], a.rdm), std::max(cell[1], a.rdm),
                                std::max(cell[2], std::abs(a.mag - 1))};
                    }
            nlohmann::json by_eccentricity = nlohmann::json::array();
            for (const auto& [eccentricity, cell] : per_eccentricity) {
                std::printf("eccentricity %.2f: RDM %.4f-%.4f, worst |MAG - 1| %.4f\n", eccentricity, cell[0], cell[1],
                            cell[2]);
                by_eccentricity.push_back({{"eccentricity", eccentricity},
                                           {"min_rdm", cell[0]},
                                           {"max_rdm", cell[1]},
                                           {"worst_mag_error", cell[2]}});
            }
            std::printf("%s: %zu nodes, %zu surface nodes, %s: worst RDM %.4f, worst |MAG - 1| %.4f over %zu dipoles\n",
                        input.c_str(), mesh.vertex_count(), surface.size(), model_name.c_str(), worst_rdm, worst_mag,
                        dipoles.size());
            context.summary = {
                {"nodes", mesh.vertex_count()},
                {"surface_nodes", surface.size()},
                {"dipole_model", model_name == "partial-integration" ? "partial_integration" : model_name},
                {"directions", directions},
                {"dipoles", dipoles},
                {"by_eccentricity", by_eccentricity},
                {"worst_rdm", worst_rdm},
                {"worst_mag_error", worst_mag},
                {"solve_seconds", seconds}};
        });
}

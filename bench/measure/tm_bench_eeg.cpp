// tm-bench-eeg: EEG forward accuracy of any tet mesh of the 4-shell sphere head (phantom spheres4:
// brain, CSF, skull, scalp to radii 78/80/86/92 mm). Radial and tangential dipoles at chosen
// eccentricities of the brain are solved on the mesh and compared on its outer surface nodes with the
// analytic series (fem/sphere_series.h): RDM on the 0..2 scale and MAG, both average-referenced. The same
// measure for every mesher (our pipeline, CGAL), so meshes can be compared at matched accuracy.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "bench/measure/spheres4_head.h"
#include "core/error.h"
#include "fem/conductivities.h"
#include "fem/outer_boundary.h"
#include "fem/solve_potential.h"
#include "fem/sphere_series.h"
#include "io/read_label_image.h"
#include "io/tet_mesh_io.h"
#include "tools/run_tool.h"

using namespace tissuemesh;

int main(int argc, char** argv)
{
    std::string input, labels;
    std::vector<double> eccentricities{0.5, 0.9};
    bool partial_integration = false;
    return tools::run_tool(
        argc, argv,
        {"tm-bench-eeg",
         "EEG forward accuracy of a tet mesh of the 4-shell sphere head (tm-phantom spheres4; its tissues named "
         "brain, csf, skull, scalp, conductivities 0.33/1.79/0.01/0.43 S/m): radial and tangential dipoles "
         "(1e-8 A*m) on the z axis at the given eccentricities of the 78 mm brain, solved by AMG-CG to 1e-10 and "
         "compared with the analytic series on the mesh's outer surface nodes. RDM (0..2) and MAG, average "
         "reference; the worst over the dipoles in --json.",
         "Example:\n  tm-bench-eeg -i cgal.msh --labels spheres4.labels.json --eccentricities 0.5,0.9 --json eeg.json"},
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
            app.add_flag("--partial-integration", partial_integration,
                         "Partial integration instead of the subtraction approach");
        },
        [&](tools::ToolContext& context) {
            TetMesh mesh = io::read_tet_mesh(input);
            if (!labels.empty()) mesh.names = io::read_tissue_names(labels);
            const fem::Conductivities sigma = tools::with_source(
                input, [&] { return fem::resolve_conductivities(mesh, bench::spheres4_conductivities, false); });
            const std::vector<std::uint32_t> surface = fem::outer_boundary(mesh).nodes;
            nlohmann::json dipoles = nlohmann::json::array();
            double worst_rdm = 0, worst_mag = 0, seconds = 0;
            for (const double eccentricity : eccentricities)
                for (const bool radial : {true, false}) {
                    const Vec3 position{0, 0, eccentricity * bench::spheres4_series.radii_mm[0]};
                    const Vec3 moment = radial ? Vec3{0, 0, 1e-8} : Vec3{1e-8, 0, 0};
                    fem::PotentialProblem problem;
                    problem.dipoles = {{position, moment}};
                    problem.dipole_model =
                        partial_integration ? fem::DipoleModel::partial_integration : fem::DipoleModel::subtraction;
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
                                       ": RDM ", a.rdm, ", MAG ", a.mag));
                    dipoles.push_back(
                        {{"eccentricity", eccentricity}, {"radial", radial}, {"rdm", a.rdm}, {"mag", a.mag}});
                    worst_rdm = std::max(worst_rdm, a.rdm);
                    worst_mag = std::max(worst_mag, std::abs(a.mag - 1));
                }
            std::printf("%s: %zu nodes, %zu surface nodes: worst RDM %.4f, worst |MAG - 1| %.4f over %zu dipoles\n",
                        input.c_str(), mesh.vertex_count(), surface.size(), worst_rdm, worst_mag, dipoles.size());
            context.summary = {{"nodes", mesh.vertex_count()},
                               {"surface_nodes", surface.size()},
                               {"dipole_model", partial_integration ? "partial_integration" : "subtraction"},
                               {"dipoles", dipoles},
                               {"worst_rdm", worst_rdm},
                               {"worst_mag_error", worst_mag},
                               {"solve_seconds", seconds}};
        });
}

// EEG forward accuracy on meshes built by our own pipeline from the spheres4 phantom (issue: fields
// verified against analytic solutions): extract -> smooth -> decimate -> remesh -> tetrahedralize -> solve,
// against the 4-shell series. RDM on the 0..2 scale, average reference (sphere_series.h).
#include <cstdio>
#include <gtest/gtest.h>

#include "fem/outer_boundary.h"
#include "fem/solve_potential.h"
#include "fem/sphere_series.h"
#include "image/phantom.h"
#include "surface/decimate.h"
#include "surface/extract_interfaces.h"
#include "surface/remesh.h"
#include "surface/smooth.h"
#include "volume/tetrahedralize.h"

namespace tissuemesh::fem {
namespace {

const LayeredSphere head{{78, 80, 86, 92}, {0.33, 1.79, 0.01, 0.43}};

/// Worst RDM and |MAG - 1| over radial and tangential dipoles at `eccentricities` of the brain.
std::pair<double, double> worst_agreement(const TetMesh& mesh, const char* what,
                                          const std::vector<double>& eccentricities = {0.2, 0.5, 0.8},
                                          DipoleModel model = DipoleModel::partial_integration)
{
    const Conductivities sigma = resolve_conductivities(mesh, {});
    double worst_rdm = 0, worst_mag = 0;
    for (const double eccentricity : eccentricities)
        for (const Vec3 moment : {Vec3{0, 0, 1e-8}, Vec3{1e-8, 0, 0}}) {
            const Vec3 position{0, 0, eccentricity * 78};
            PotentialProblem problem;
            problem.dipoles = {{position, moment}};
            problem.dipole_model = model;
            const std::vector<double> phi = solve_potential(mesh, sigma, problem, {.relative_tolerance = 1e-10});
            std::vector<double> numeric;
            std::vector<Vec3> points;
            for (const std::uint32_t node : outer_boundary(mesh).nodes)
                numeric.push_back(phi[node]), points.push_back(mesh.vertices[node]);
            const std::vector<double> analytic = sphere_surface_potentials(head, position, moment, points);
            const Agreement a = compare_potentials(numeric, analytic);
            std::printf("[pipeline] %s: %s %s dipole at eccentricity %.2f: RDM %.4f MAG %.4f\n", what,
                        model == DipoleModel::subtraction ? "subtraction" : "partial integration",
                        moment[2] != 0 ? "radial" : "tangential", eccentricity, a.rdm, a.mag);
            worst_rdm = std::max(worst_rdm, a.rdm);
            worst_mag = std::max(worst_mag, std::abs(a.mag - 1));
        }
    return {worst_rdm, worst_mag};
}

TEST(PipelineSpheres, LongSmoothedSurfacesAt2mm)
{
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = 2.0});
    InterfaceComplex complex = surface::extract_interfaces(phantom.image, {.priority = {{3, 1}}});
    surface::smooth(complex, phantom.image);
    surface::decimate(complex, {.max_distance_mm = 1.0});
    surface::remesh(complex, {.target_edge_mm = 3.0});
    volume::TetrahedralizeReport report;
    // Tets up to 10 mm^3 as in the icosphere tests (test_four_shell.cpp): large brain tets around the
    // dipole cost more accuracy than the surfaces.
    const TetMesh mesh = volume::tetrahedralize(complex, {.max_volume_mm3 = 10}, {}, &report);
    std::printf("[pipeline] %zu triangles -> %zu tets, %zu nodes, min dihedral %.2f deg\n", complex.triangle_count(),
                mesh.tet_count(), mesh.vertex_count(), report.min_dihedral_deg);
    const auto [rdm, mag] = worst_agreement(mesh, "spheres4 2 mm, smoothed + decimated + remeshed (3 mm)");
    // Measured: RDM 0.014-0.038 and |MAG - 1| <= 0.006 over the six dipoles (121 k nodes, 713 k tets); on the
    // terraced (unsmoothed) 2 mm surfaces the RDM was 0.18. The target (RDM 0.02) is for 1 mm voxels.
    EXPECT_LT(rdm, 0.06);
    EXPECT_LT(mag, 0.02);
}

/// The 1 mm phantom through the same chain (decimation bound 0.5 mm, 2 mm interface edges, tets up to
/// 10 mm^3: 188 k nodes, 1.04 M tets), both dipole models at eccentricities 0.2 to 0.95 (0.95: 3.9 mm from
/// the CSF). Measured, subtraction (radial / tangential RDM, MAG): 0.2: 0.0023 / 0.0019, 1.006 / 1.005;
/// 0.5: 0.0039 / 0.0029, 1.008 / 1.005; 0.8: 0.0079 / 0.0084, 1.013 / 1.007; 0.9: 0.0139 / 0.0140,
/// 1.014 / 1.009; 0.95: 0.0224 / 0.0200, 1.016 / 1.007. Partial integration: RDM 0.012-0.039, MAG up to
/// 1.034 (worst at 0.95, radial). About 12 minutes on 2 shared cores (most of it smoothing the 1 mm surfaces).
TEST(PipelineSpheres, LongSmoothedSurfacesAt1mm)
{
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = 1.0});
    InterfaceComplex complex = surface::extract_interfaces(phantom.image, {.priority = {{3, 1}}});
    surface::smooth(complex, phantom.image);
    surface::decimate(complex, {.max_distance_mm = 0.5});
    surface::remesh(complex, {.target_edge_mm = 2.0});
    volume::TetrahedralizeReport report;
    const TetMesh mesh = volume::tetrahedralize(complex, {.max_volume_mm3 = 10}, {}, &report);
    std::printf("[pipeline] %zu triangles -> %zu tets, %zu nodes, min dihedral %.2f deg\n", complex.triangle_count(),
                mesh.tet_count(), mesh.vertex_count(), report.min_dihedral_deg);
    const char* what = "spheres4 1 mm, smoothed + decimated + remeshed (2 mm)";
    const auto [rdm, mag] = worst_agreement(mesh, what, {0.2, 0.5, 0.8, 0.9}, DipoleModel::subtraction);
    const auto [rdm_95, mag_95] = worst_agreement(mesh, what, {0.95}, DipoleModel::subtraction);
    const auto [rdm_pi, mag_pi] = worst_agreement(mesh, what, {0.2, 0.5, 0.8, 0.9, 0.95});
    std::printf("[pipeline] worst subtraction 0.2-0.9: RDM %.4f |MAG - 1| %.4f; 0.95: RDM %.4f |MAG - 1| %.4f; "
                "partial integration 0.2-0.95: RDM %.4f |MAG - 1| %.4f\n", rdm, mag, rdm_95, mag_95, rdm_pi, mag_pi);
    // The targets up to eccentricity 0.9 (measured worst 0.0140 and 0.0137); at 0.95 the measured
    // worst (0.0224, 0.0155) plus a margin; partial integration as a check that both models agree.
    EXPECT_LT(rdm, 0.02);
    EXPECT_LT(mag, 0.02);
    EXPECT_LT(rdm_95, 0.03);
    EXPECT_LT(mag_95, 0.02);
    EXPECT_LT(rdm_pi, 0.05);
    EXPECT_LT(mag_pi, 0.05);
}

} // namespace
} // namespace tissuemesh::fem

// Dipoles in the 4-shell sphere head against the analytic series (sphere_series.h). RDM is on the 0..2
// scale, MAG the ratio of norms, both over the outer surface nodes after subtracting each potential's
// mean (average reference).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fem/outer_boundary.h"
#include "fem/solve_potential.h"
#include "fem/sphere_series.h"
#include "fem_meshes.h"

namespace tissuemesh::fem {
namespace {

TEST(SphereSeries, MatchesTheClosedFormsItReducesTo)
{
    // One homogeneous sphere, centred dipole: 3 p . r_hat / (4 pi sigma R^2) (see test_dipole.cpp).
    const LayeredSphere ball{{50}, {0.33}};
    const Vec3 p{0, 0.6e-8, 0.8e-8}, point{30, 0, 40};
    const double closed = 3 * dot(p, Vec3{0.6, 0, 0.8}) / (4 * std::numbers::pi * 0.33 * 0.05 * 0.05);
    EXPECT_NEAR(sphere_surface_potential(ball, {0, 0, 0}, p, point), closed, 1e-12 * std::abs(closed));
    // Four layers of one conductivity are one sphere, also for an eccentric oblique dipole.
    const LayeredSphere same{{78, 80, 86, 92}, {0.33, 0.33, 0.33, 0.33}}, one{{92}, {0.33}};
    const Vec3 position{10, -20, 40}, moment{1e-8, 2e-8, -0.5e-8}, surface{0, 92 * 0.6, 92 * 0.8};
    const double layered = sphere_surface_potential(same, position, moment, surface);
    EXPECT_NEAR(layered, sphere_surface_potential(one, position, moment, surface), 1e-10 * std::abs(layered));
}

void expect_dipole_agreement(const TetMesh& mesh, const Vec3& position, const Vec3& moment, double max_rdm,
                             double max_mag_error, DipoleModel model = DipoleModel::partial_integration)
{
    PotentialProblem problem;
    problem.dipoles = {{position, moment}};
    problem.dipole_model = model;
    PotentialReport report;
    const std::vector<double> phi =
        solve_potential(mesh, resolve_conductivities(mesh, {}), problem, {.relative_tolerance = 1e-10}, {}, &report);
    std::vector<double> numeric;
    std::vector<Vec3> points;
    for (std::uint32_t node : outer_boundary(mesh).nodes)
        numeric.push_back(phi[node]), points.push_back(mesh.vertices[node]);
    const std::vector<double> analytic =
        sphere_surface_potentials(testing::four_shell_series, position, moment, points);
    const Agreement a = compare_potentials(numeric, analytic);
    const char* name = model == DipoleModel::subtraction ? "subtraction"
                       : model == DipoleModel::venant    ? "Venant"
                                                         : "partial integration";
    std::printf(
        "[4-shell] %s dipole at (%.0f, %.0f, %.0f) mm moment (%.0e, %.0e, %.0e): %zu nodes, RDM %.4f, MAG %.4f, "
        "%d AMG-CG iterations\n",
        name, position[0], position[1], position[2], moment[0], moment[1], moment[2], mesh.vertex_count(), a.rdm, a.mag,
        report.solver.iterations);
    EXPECT_LT(a.rdm, max_rdm);
    EXPECT_NEAR(a.mag, 1.0, max_mag_error);
}

// Icosphere level 4 (surface edges 3.3 to 5.5 mm, one 2 mm CSF layer), tets up to 10 mm^3: 62 k nodes,
// ~5 s (most of it building the mesh). Measured at eccentricity 0.5 (of the 78 mm brain), partial
// integration: radial RDM 0.019 MAG 1.001, tangential RDM 0.020 MAG 1.005; the multipolar Venant model
// (fem/detail/venant.h) on the same mesh: radial RDM 0.0027 MAG 1.0035, tangential RDM 0.0041 MAG 1.0041,
// as good as subtraction (0.0030, 0.0024, below): partial integration's loads carry the quadrupole of their
// one tet, Venant's none. The bounds leave room for other TetGen versions (a sign, unit or
// interface-condition error moves RDM or MAG by far more).
TEST(FourShellHead, RadialAndTangentialDipolesAtHalfEccentricity)
{
    const TetMesh mesh = testing::four_shell_head(4, 10.0);
    expect_dipole_agreement(mesh, {0, 0, 39}, {0, 0, 1e-8}, 0.03, 0.02);
    expect_dipole_agreement(mesh, {0, 0, 39}, {1e-8, 0, 0}, 0.03, 0.02);
    expect_dipole_agreement(mesh, {0, 0, 39}, {0, 0, 1e-8}, 0.01, 0.01, DipoleModel::venant);
    expect_dipole_agreement(mesh, {0, 0, 39}, {1e-8, 0, 0}, 0.01, 0.01, DipoleModel::venant);
}

// Eccentricities 0.2 to 0.9 of the brain radius on the same mesh. Measured: RDM 0.010 to 0.032, MAG
// 0.996 to 1.005 (worst RDM at 0.8, radial). The target (RDM and |MAG - 1| under 2%) is met
// for MAG everywhere and for RDM at 0.2 to 0.7, not at 0.8 and 0.9 (up to 0.032) on this 62 k-node
// mesh; the bounds here are the measured worst plus a margin.
TEST(FourShellHead, EccentricitiesLong)
{
    const TetMesh mesh = testing::four_shell_head(4, 10.0);
    for (double eccentricity : {0.2, 0.5, 0.7, 0.8, 0.9}) {
        const Vec3 position{0, 0, 78 * eccentricity};
        expect_dipole_agreement(mesh, position, {0, 0, 1e-8}, 0.05, 0.02);
        expect_dipole_agreement(mesh, position, {1e-8, 0, 0}, 0.05, 0.02);
    }
}

// The subtraction approach on the same mesh: the singular part is exact, so the error left is the P1
// error of the smooth correction. Measured at eccentricity 0.5: radial RDM 0.0030 MAG 1.0038, tangential
// RDM 0.0024 MAG 1.0036 (partial integration: 0.019 and 0.020 above).
TEST(FourShellHead, SubtractionAtHalfEccentricity)
{
    const TetMesh mesh = testing::four_shell_head(4, 10.0);
    expect_dipole_agreement(mesh, {0, 0, 39}, {0, 0, 1e-8}, 0.01, 0.01, DipoleModel::subtraction);
    expect_dipole_agreement(mesh, {0, 0, 39}, {1e-8, 0, 0}, 0.01, 0.01, DipoleModel::subtraction);
}

// Up to eccentricity 0.95 (3.9 mm from the CSF, about one brain element of this mesh). Measured
// (radial / tangential RDM, MAG): 0.8: 0.0089 / 0.0069, 1.006 / 1.005; 0.9: 0.0185 / 0.0122, 1.008 / 1.006;
// 0.95: 0.0375 / 0.0223, 1.007 / 1.006. Partial integration on the same mesh: 0.8: 0.032 / 0.024; 0.9:
// 0.020 / 0.024; 0.95: 0.024 / 0.036. Near the interface the correction itself is steep and this 62 k-node
// mesh is too coarse for it: the bounds are the measured worst plus a margin.
TEST(FourShellHead, SubtractionEccentricitiesLong)
{
    const TetMesh mesh = testing::four_shell_head(4, 10.0);
    for (double eccentricity : {0.8, 0.9, 0.95}) {
        const Vec3 position{0, 0, 78 * eccentricity};
        const double max_rdm = eccentricity < 0.85 ? 0.015 : eccentricity < 0.925 ? 0.025 : 0.05;
        expect_dipole_agreement(mesh, position, {0, 0, 1e-8}, max_rdm, 0.015, DipoleModel::subtraction);
        expect_dipole_agreement(mesh, position, {1e-8, 0, 0}, max_rdm, 0.015, DipoleModel::subtraction);
    }
}

// The Venant model at eccentricities 0.2 to 0.95. Measured (radial / tangential RDM, MAG): 0.2: 0.0022 /
// 0.0024, 1.003 / 1.003; 0.5: 0.0027 / 0.0041, 1.004 / 1.004; 0.8: 0.0062 / 0.0033, 1.005 / 1.003; 0.9:
// 0.0163 / 0.0095, 1.010 / 1.005; 0.95: 0.0305 / 0.0126, 1.015 / 1.004. The target (RDM and |MAG - 1| under 2%)
// holds up to 0.9 on this 62 k-node mesh, where partial integration reaches 0.032 and subtraction 0.0185
// (0.95: 3.9 mm from the CSF, one brain element: subtraction 0.0375, partial integration 0.036). Over 13
// directions at 0.9 Venant stayed at or under 0.0184 (docs/fem.md).
TEST(FourShellHead, VenantEccentricitiesLong)
{
    const TetMesh mesh = testing::four_shell_head(4, 10.0);
    for (double eccentricity : {0.2, 0.5, 0.8, 0.9, 0.95}) {
        const Vec3 position{0, 0, 78 * eccentricity};
        const double max_rdm = eccentricity < 0.925 ? 0.02 : 0.04;
        expect_dipole_agreement(mesh, position, {0, 0, 1e-8}, max_rdm, 0.02, DipoleModel::venant);
        expect_dipole_agreement(mesh, position, {1e-8, 0, 0}, max_rdm, 0.02, DipoleModel::venant);
    }
}

} // namespace
} // namespace tissuemesh::fem

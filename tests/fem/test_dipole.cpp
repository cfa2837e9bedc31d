// A current dipole at the centre of a homogeneous sphere (radius R, conductivity sigma, insulated
// surface). Exact potential: phi = p cos(theta) / (4 pi sigma) (1 / r^2 + 2 r / R^3): both terms are
// harmonic and the radial derivative vanishes at r = R. On the surface: 3 p . r_hat / (4 pi sigma R^2).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.h"
#include "fem/outer_boundary.h"
#include "fem/solve_potential.h"
#include "fem/sphere_series.h"
#include "fem_meshes.h"
#include "tests/io/expect_error.h"

namespace tissuemesh::fem {
namespace {

TEST(Dipole, CentredDipoleInAHomogeneousSphere)
{
    const double radius_mm = 50;
    // Surface edges ~3.3 mm (icosphere level 4), tets up to 5 mm^3: 30 k nodes, ~2 s.
    const TetMesh mesh = testing::ball_mesh(radius_mm, 4, 5.0);
    const Conductivities sigma = resolve_conductivities(mesh, {}); // brain: 0.33 S/m by default
    PotentialProblem problem;
    const Vec3 moment{0, 0.6e-8, 0.8e-8}; // A*m (10 nA m, oblique)
    problem.dipoles = {{.position_mm = {0, 0, 0}, .moment_am = moment}};
    PotentialReport report;
    const std::vector<double> phi = solve_potential(mesh, sigma, problem, {.relative_tolerance = 1e-12}, {}, &report);
    // Relative difference measure (0..2) and magnitude ratio on the surface nodes, both average-referenced.
    const std::vector<std::uint32_t> surface = outer_boundary(mesh).nodes;
    std::vector<double> numeric, analytic;
    const double r_m = radius_mm * 1e-3;
    for (std::uint32_t node : surface) {
        const Vec3& x = mesh.vertices[node];
        numeric.push_back(phi[node]);
        analytic.push_back(3 * dot(moment, (1 / norm(x)) * x) / (4 * std::numbers::pi * 0.33 * r_m * r_m));
    }
    const auto [rdm, mag] = compare_potentials(numeric, analytic);
    std::printf("[dipole] %zu nodes, %zu surface nodes: RDM %.4f, MAG %.4f, %d AMG-CG iterations\n",
                mesh.vertex_count(), surface.size(), rdm, mag, report.solver.iterations);
    // Measured: RDM 0.035, MAG 1.003. Partial integration reproduces the dipole moment exactly (sum of
    // b_i x_i = p) but adds a spurious quadrupole of the size of the source tet (~2 mm here), and the
    // 3 mm flat surface faces add their own error: a few percent RDM. A sign, unit or pattern error
    // gives RDM ~2 or MAG off by orders of magnitude.
    EXPECT_LT(rdm, 0.05);
    EXPECT_NEAR(mag, 1.0, 0.02);
}

// The same sphere by subtraction, the dipole 2 mm off the centre (the centre is a node, where the
// unbounded-medium potential is infinite), against the one-layer series (sphere_series.h). The singular
// part is exact; only the smooth correction (the reflection at the insulated surface) is P1-approximated.
// Measured: RDM 0.0001, MAG 1.0014 (partial integration at the centre above: RDM 0.035).
TEST(Dipole, OffCentreDipoleBySubtraction)
{
    const TetMesh mesh = testing::ball_mesh(50, 4, 5.0);
    PotentialProblem problem;
    const Vec3 position{1.2, -0.8, 1.4}, moment{0, 0.6e-8, 0.8e-8};
    problem.dipoles = {{.position_mm = position, .moment_am = moment}};
    problem.dipole_model = DipoleModel::subtraction;
    const std::vector<double> phi =
        solve_potential(mesh, resolve_conductivities(mesh, {}), problem, {.relative_tolerance = 1e-12});
    std::vector<double> numeric;
    std::vector<Vec3> points;
    for (std::uint32_t node : outer_boundary(mesh).nodes)
        numeric.push_back(phi[node]), points.push_back(mesh.vertices[node]);
    const std::vector<double> analytic = sphere_surface_potentials({{50}, {0.33}}, position, moment, points);
    const auto [rdm, mag] = compare_potentials(numeric, analytic);
    std::printf("[dipole] subtraction: RDM %.4f, MAG %.4f\n", rdm, mag);
    EXPECT_LT(rdm, 0.01);
    EXPECT_NEAR(mag, 1.0, 0.01);
    // On the centre node it is refused with the reason.
    problem.dipoles[0].position_mm = {0, 0, 0};
    EXPECT_THROW(solve_potential(mesh, resolve_conductivities(mesh, {}), problem), InputError);
}

TEST(Dipole, SubtractionInAnAnisotropicTissueIsAnInputError)
{
    // phi_inf is the unbounded-medium potential of an isotropic conductivity.
    const TetMesh mesh = testing::box_mesh(5, 20.0);
    PotentialProblem problem;
    problem.dipoles = {{.position_mm = {9, 10.3, 10.1}, .moment_am = {0, 0, 1e-8}}};
    problem.dipole_model = DipoleModel::subtraction;
    const Mat3 tensor{0.5, 0, 0, 0, 0.1, 0, 0, 0, 0.1};
    // Subtraction in an anisotropic tissue must be refused.
    testing::expect_error<InputError>(
        [&] {
            solve_potential(mesh, resolve_conductivities(mesh, {{"1", tensor}}), problem);
        },
        {"lies in an anisotropic tissue"});
}

TEST(Dipole, OutsideTheMeshIsAnInputError)
{
    const TetMesh mesh = testing::box_mesh(2, 10.0);
    PotentialProblem problem;
    problem.dipoles = {{.position_mm = {5, 5, 12}, .moment_am = {0, 0, 1e-8}}};
    // A dipole outside the mesh must be refused.
    testing::expect_error<InputError>(
        [&] {
            solve_potential(mesh, resolve_conductivities(mesh, {{"1", isotropic(0.33)}}), problem);
        },
        {"dipole 1 at (5, 5, 12) mm lies outside the mesh"});
}

} // namespace
} // namespace tissuemesh::fem

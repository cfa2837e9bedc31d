// Patch tests: P1 elements reproduce linear potentials exactly, so these must hold to round-off.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "fem/assemble.h"
#include "fem/compute_fields.h"
#include "fem/outer_boundary.h"
#include "fem/solve_potential.h"
#include "fem_meshes.h"
#include "tests/io/expect_error.h"

namespace tissuemesh::fem {
namespace {

double linear(const Vec3& p) { return 0.7 + 0.01 * p[0] - 0.02 * p[1] + 0.005 * p[2]; } // V, p in mm

// A linear potential imposed on the boundary is reproduced inside, on a jittered mesh with two tissues of
// the same anisotropic tensor (a constant tensor keeps every linear field a solution).
void expect_patch_test(Preconditioner preconditioner)
{
    const TetMesh mesh = testing::box_mesh(6, 12.0, 0.2, [](const Vec3& c) { return Label(c[2] < 6 ? 1 : 2); });
    const Mat3 tensor{0.5, 0.1, 0.0, 0.1, 0.3, 0.05, 0.0, 0.05, 0.2};
    const Conductivities sigma = resolve_conductivities(mesh, {{"1", tensor}, {"2", tensor}});
    PotentialProblem problem;
    for (std::uint32_t node : outer_boundary(mesh).nodes) {
        problem.fixed.nodes.push_back(node);
        problem.fixed.values_v.push_back(linear(mesh.vertices[node]));
    }
    PotentialReport report;
    const std::vector<double> phi = solve_potential(
        mesh, sigma, problem, {.preconditioner = preconditioner, .relative_tolerance = 1e-14}, {}, &report);
    EXPECT_EQ(report.unknowns, 5u * 5u * 5u); // interior nodes of a 7^3 grid
    double worst = 0;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
        worst = std::max(worst, std::abs(phi[v] - linear(mesh.vertices[v])));
    // Potentials are O(1) V; residual 1e-14 on a well-conditioned 125-unknown system: 1e-12 V is round-off.
    EXPECT_LT(worst, 1e-12) << report.solver.preconditioner << " " << report.solver.iterations << " iterations";
}

TEST(PatchTest, LinearPotentialReproducedJacobi) { expect_patch_test(Preconditioner::jacobi); }
TEST(PatchTest, LinearPotentialReproducedAmg) { expect_patch_test(Preconditioner::amg); }

// Electrodes covering two opposite faces of a box: uniform current density I / A, so the exact potential
// is linear and P1 must reproduce it; its slope checks the mm -> m convention:
// phi(0) - phi(L) = I L / (sigma A) with L and A in metres.
Electrode face_electrode(double x_mm, double size_mm, double outward)
{
    const double away = 10 * size_mm; // centre far behind the face: the sphere cuts only that face
    Electrode electrode;
    electrode.centre_mm = {x_mm + outward * away, size_mm / 2, size_mm / 2};
    electrode.radius_mm = std::sqrt(away * away + size_mm * size_mm / 2) * (1 + 1e-9);
    return electrode;
}

TEST(Electrodes, CurrentThroughABoxGivesTheExactOhmicDrop)
{
    const double size_mm = 20;
    const TetMesh mesh = testing::box_mesh(5, size_mm, 0.2);
    const Conductivities sigma = resolve_conductivities(mesh, {{"1", isotropic(0.5)}});
    PotentialProblem problem;
    problem.electrodes = {face_electrode(0, size_mm, -1), face_electrode(size_mm, size_mm, 1)};
    problem.electrodes[0].current_a = 2e-3;
    problem.electrodes[1].current_a = -2e-3;
    PotentialReport report;
    const std::vector<double> phi = solve_potential(mesh, sigma, problem, {.relative_tolerance = 1e-13}, {}, &report);
    ASSERT_EQ(report.electrode_nodes.size(), 2u);
    EXPECT_EQ(report.electrode_nodes[0], 36u); // the 6 x 6 nodes of the face x = 0
    EXPECT_NEAR(report.electrode_area_mm2[1], size_mm * size_mm, 1e-9);
    const double length_m = size_mm * 1e-3;
    const double drop_v = 2e-3 * length_m / (0.5 * length_m * length_m); // 0.2 V
    // Zero nodal mean: the exact linear potential shifted by the nodes' mean x (interior nodes are jittered).
    double mean_x = 0;
    for (const Vec3& p : mesh.vertices) mean_x += p[0] / static_cast<double>(mesh.vertex_count());
    double mean = 0;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        const double expected = drop_v * (mean_x - mesh.vertices[v][0]) / size_mm;
        EXPECT_NEAR(phi[v], expected, 1e-12) << "node " << v;
        mean += phi[v];
    }
    EXPECT_NEAR(mean / static_cast<double>(mesh.vertex_count()), 0.0, 1e-14);
    // Uniform current density I / A = 2e-3 A / 4e-4 m^2 = 5 A/m^2 along +x in every tet (1e-9 A/m^2:
    // round-off of gradients over 4 mm edges).
    const TetFields fields = compute_fields(mesh, sigma, phi);
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
        EXPECT_NEAR(fields.current_a_per_m2[t][0], 5.0, 1e-9);
        EXPECT_NEAR(fields.current_a_per_m2[t][1], 0.0, 1e-9);
        EXPECT_NEAR(fields.electric_v_per_m[t][0], 10.0, 2e-9); // E = J / sigma
    }
}

TEST(Electrodes, FixedPotentialElectrodes)
{
    const TetMesh mesh = testing::box_mesh(4, 10.0, 0.2);
    PotentialProblem problem;
    problem.electrodes = {face_electrode(0, 10, -1), face_electrode(10, 10, 1)};
    problem.electrodes[0].mode = problem.electrodes[1].mode = Electrode::Mode::potential;
    problem.electrodes[0].potential_v = 1.0;
    const std::vector<double> phi = solve_potential(mesh, resolve_conductivities(mesh, {{"1", isotropic(0.3)}}),
                                                    problem, {.relative_tolerance = 1e-14});
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) EXPECT_NEAR(phi[v], 1 - mesh.vertices[v][0] / 10, 1e-12);
}

TEST(Electrodes, UnbalancedCurrentsAndMissedSurfaceAreInputErrors)
{
    const TetMesh mesh = testing::box_mesh(3, 10.0);
    const Conductivities sigma = resolve_conductivities(mesh, {{"1", isotropic(1)}});
    PotentialProblem problem;
    problem.electrodes = {face_electrode(0, 10, -1)};
    problem.electrodes[0].current_a = 1e-3;
    // A lone current electrode on an insulated body has no solution.
    testing::expect_error<InputError>([&] { solve_potential(mesh, sigma, problem); }, {"add a return electrode"});
    problem.electrodes = {Electrode{.centre_mm = {50, 50, 50}, .radius_mm = 3}};
    // An electrode off the surface must be refused.
    testing::expect_error<InputError>([&] { solve_potential(mesh, sigma, problem); },
                                      {"electrode 1 at (50, 50, 50) mm with radius 3 mm covers 0 boundary"});
}

TEST(Solver, CapReachedIsAnAlgorithmError)
{
    const TetMesh mesh = testing::box_mesh(6, 12.0, 0.2);
    PotentialProblem problem;
    problem.fixed = {{0, static_cast<std::uint32_t>(mesh.vertex_count() - 1)}, {1.0, 0.0}};
    // 3 Jacobi-CG iterations cannot reach 1e-10.
    testing::expect_error<AlgorithmError>(
        [&] {
            solve_potential(mesh, resolve_conductivities(mesh, {{"1", isotropic(1)}}), problem,
                            {.preconditioner = Preconditioner::jacobi, .max_iterations = 3});
        },
        {"after 3 iterations"});
}

} // namespace
} // namespace tissuemesh::fem

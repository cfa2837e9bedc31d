// The flux-jump error indicator: zero where P1 is exact, shrinking under refinement, largest where the
// solution bends most.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fem/estimate_error.h"
#include "fem/outer_boundary.h"
#include "fem/solve_potential.h"
#include "fem_meshes.h"

namespace tissuemesh::fem {
namespace {

TEST(EstimateError, ZeroForALinearPotential)
{
    const TetMesh mesh = testing::box_mesh(4, 10.0, 0.2);
    std::vector<double> phi;
    for (const Vec3& p : mesh.vertices) phi.push_back(0.3 + 0.02 * p[0] - 0.01 * p[2]);
    const std::vector<double> eta = estimate_error(mesh, resolve_conductivities(mesh, {{"1", isotropic(0.5)}}), phi);
    ASSERT_EQ(eta.size(), mesh.tet_count());
    // Fields of 10-20 V/m on mm faces: jumps are round-off, eta ~ 1e-14 A/sqrt(m) at most.
    EXPECT_LT(*std::max_element(eta.begin(), eta.end()), 1e-12);
}

// Total indicator of the concentric-shell problem (1 V over 10..30 mm, two layers).
double shell_indicator(int levels, double max_volume_mm3, double* inner_share)
{
    const TetMesh mesh = testing::shell_mesh({10, 20, 30}, levels, max_volume_mm3);
    PotentialProblem problem;
    for (std::uint32_t node : outer_boundary(mesh).nodes) {
        problem.fixed.nodes.push_back(node);
        problem.fixed.values_v.push_back(norm(mesh.vertices[node]) < 20 ? 1.0 : 0.0);
    }
    const Conductivities sigma = resolve_conductivities(mesh, {{"1", isotropic(1.0)}, {"2", isotropic(0.25)}});
    const std::vector<double> eta = estimate_error(mesh, sigma, solve_potential(mesh, sigma, problem));
    double total = 0, inner = 0;
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
        Vec3 c{0, 0, 0};
        for (std::uint32_t v : mesh.tets[t]) c = c + 0.25 * mesh.vertices[v];
        total += eta[t] * eta[t];
        if (norm(c) < 15) inner += eta[t] * eta[t];
    }
    *inner_share = inner / total;
    return std::sqrt(total);
}

TEST(EstimateError, ShrinksUnderRefinementAndPointsAtTheSteepRegion)
{
    double coarse_inner = 0, fine_inner = 0;
    const double coarse = shell_indicator(2, 8.0, &coarse_inner);
    const double fine = shell_indicator(3, 1.0, &fine_inner);
    std::printf("[estimate] total indicator %.3e -> %.3e (ratio %.2f); share of r < 15 mm %.2f, %.2f\n", coarse, fine,
                coarse / fine, coarse_inner, fine_inner);
    // Energy-norm error is O(h): halving the nominal size should about halve the indicator.
    EXPECT_GT(coarse / fine, 1.5);
    // The potential bends most near the inner sphere (1/r): the shell r < 15 mm holds 9% of the volume
    // ((15^3 - 10^3) / (30^3 - 10^3)) but must hold most of the indicator.
    EXPECT_GT(fine_inner, 0.5);
}

} // namespace
} // namespace tissuemesh::fem

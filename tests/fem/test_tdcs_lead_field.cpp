// The tDCS lead field (fem/tdcs_lead_field.h): any montage's potential summed from it equals a direct solve of
// that montage; and source grids (fem/source_grid.h) keep to their tissues.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "fem/source_grid.h"
#include "fem/tdcs_lead_field.h"
#include "fem_meshes.h"

namespace tissuemesh::fem {
namespace {

// Four patches on the small 4-shell head; the lead field against the third. Montages of 2 and of 4
// electrodes, the reference driven or not, against solve_potential() with those electrodes (zero mean). Both
// sides solve to 1e-12: measured differences up to 1e-11 of the potential's range.
TEST(TdcsLeadField, MontageSumsEqualDirectSolves)
{
    const TetMesh mesh = testing::four_shell_head(3, 30.0);
    const Conductivities sigma = resolve_conductivities(mesh, {});
    const std::vector<Electrode> patches{{.centre_mm = {-92, 0, 0}, .radius_mm = 15, .name = "T7"},
                                         {.centre_mm = {92, 0, 0}, .radius_mm = 15, .name = "T8"},
                                         {.centre_mm = {0, 0, 92}, .radius_mm = 15, .name = "Cz"},
                                         {.centre_mm = {0, 92, 0}, .radius_mm = 20, .name = "Fpz"}};
    const SolverOptions solver{.relative_tolerance = 1e-12, .processes = 1};
    TdcsLeadFieldReport report;
    const TdcsLeadField lead_field = compute_tdcs_lead_field(mesh, sigma, patches, 2, solver, {}, &report);
    ASSERT_EQ(lead_field.electrodes, (std::vector<std::size_t>{0, 1, 3}));
    ASSERT_EQ(lead_field.potentials_v_per_a.rows(), 3);
    EXPECT_EQ(report.solver.columns, 3u);
    for (const std::vector<double>& currents :
         {std::vector<double>{1e-3, -1e-3, 0, 0}, std::vector<double>{1e-3, 0, -2.5e-4, -7.5e-4},
          std::vector<double>{0, 2e-3, 0, -2e-3}}) {
        PotentialProblem problem;
        for (std::size_t e = 0; e < patches.size(); ++e)
            if (currents[e] != 0) {
                Electrode electrode = patches[e];
                electrode.current_a = currents[e];
                problem.electrodes.push_back(electrode);
            }
        const std::vector<double> direct = solve_potential(mesh, sigma, problem, solver);
        const std::vector<double> summed = montage_potential(lead_field, currents);
        const auto [low, high] = std::minmax_element(direct.begin(), direct.end());
        double worst = 0;
        for (std::size_t i = 0; i < direct.size(); ++i) worst = std::max(worst, std::abs(direct[i] - summed[i]));
        EXPECT_LT(worst, 1e-9 * (*high - *low)) << worst << " V of " << *high - *low << " V";
    }
    EXPECT_THROW(montage_potential(lead_field, {1e-3, 0, 0, 0}), InputError); // nothing comes out
    EXPECT_THROW(montage_potential(lead_field, {1e-3, -1e-3}), InputError);
}

// A 10 mm grid in the brain (radius 78 mm, an inscribed icosphere), 5 mm from the CSF: every point lies in the
// brain and at most 73 mm from the centre, and nearly all grid points of the 73 mm ball are there (the
// polyhedron lies up to 0.6 mm inside the sphere at this level).
TEST(SourceGrid, PointsLieInTheirTissueAwayFromItsBoundary)
{
    const TetMesh mesh = testing::four_shell_head(3, 30.0);
    const std::vector<Vec3> points = source_grid(mesh, {.spacing_mm = 10, .tissues = {4}, .min_distance_mm = 5});
    std::size_t in_ball = 0;
    for (int x = -7; x <= 7; ++x)
        for (int y = -7; y <= 7; ++y)
            for (int z = -7; z <= 7; ++z) in_ball += std::sqrt(x * x + y * y + z * z) * 10 <= 72.0;
    for (const Vec3& p : points) {
        EXPECT_LE(norm(p), 73.0 + 1e-9);
        for (const double c : p) EXPECT_EQ(std::fmod(std::abs(c), 10.0), 0.0);
    }
    EXPECT_GE(points.size(), in_ball);
    EXPECT_LE(points.size(), in_ball + 60);
    // Without the distance the grid reaches the brain's surface; the skull shell holds no point at r < 80.
    const std::vector<Vec3> skull = source_grid(mesh, {.spacing_mm = 4, .tissues = {2}});
    ASSERT_FALSE(skull.empty());
    for (const Vec3& p : skull) EXPECT_GE(norm(p), 79.0);
    EXPECT_THROW(source_grid(mesh, {.spacing_mm = 10, .tissues = {}}), InputError);
    EXPECT_THROW(source_grid(mesh, {.spacing_mm = 10, .tissues = {7}}), InputError);
    EXPECT_THROW(source_grid(mesh, {.spacing_mm = 0.05, .tissues = {4}}), InputError); // 2.7e10 grid points
}

} // namespace
} // namespace tissuemesh::fem

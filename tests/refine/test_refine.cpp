// Adaptive refinement: the error volume falls as nodes grow (Delaunay-only), the incremental assessment equals a
// full one, and constrained refinement keeps every interface and the error volume.
#include <gtest/gtest.h>

#include "image/phantom.h"
#include "surface/extract_interfaces.h"
#include "volume/assess.h"
#include "volume/check_mesh.h"
#include "volume/refine.h"
#include "volume/tetrahedralize.h"

namespace tissuemesh::volume {
namespace {

/// spheres4 with 8 mm voxels: 27^3 voxels, coarse enough for a few seconds of refinement.
const LabelImage& coarse_head()
{
    static const LabelImage image = image::make_phantom("spheres4", {.voxel_mm = 8}).image;
    return image;
}

TEST(RefineDelaunay, ErrorVolumeFallsAsNodesGrow)
{
    RefineReport report;
    const TetMesh mesh = refine(coarse_head(), nullptr, {.max_iterations = 12}, {}, &report);
    ASSERT_GE(report.iterations.size(), 2u);
    const RefineIteration& first = report.iterations.front();
    const RefineIteration& last = report.iterations.back();
    for (std::size_t i = 1; i < report.iterations.size(); ++i)
        EXPECT_GT(report.iterations[i].nodes, report.iterations[i - 1].nodes) << "round " << i;
    // Not every round must lower the error (a new tet can straddle a tissue change the old one missed), but
    // the trend must be clear: at most a quarter of the start after 12 rounds.
    EXPECT_LT(last.total_error_volume_mm3, 0.25 * first.total_error_volume_mm3)
        << first.total_error_volume_mm3 << " mm^3 at " << first.nodes << " nodes, " << last.total_error_volume_mm3
        << " mm^3 at " << last.nodes;
    EXPECT_EQ(mesh.vertices.size(), last.nodes);
    // The improver (on by default, without insertion) keeps the last round's nodes; its flips change the tets.
    ASSERT_TRUE(report.improved);
    EXPECT_EQ(report.improvement.before.tets, last.tets);
    EXPECT_EQ(mesh.tets.size(), report.improvement.after.tets);
}

TEST(RefineDelaunay, IncrementalAssessmentEqualsAFullOneAndTheMeshIsValid)
{
    RefineReport report;
    // Without the improver: the last round's assessment is of the last round's mesh.
    const TetMesh mesh = refine(coarse_head(), nullptr, {.max_iterations = 6, .improve = false}, {}, &report);
    const Assessment full = assess_elements(mesh, coarse_head());
    // Unchanged tets keep their counts, new ones are rasterized with the same per-face rule, so the sums would be
    // equal but for rasterize_tets' floating-point face tests: a voxel centre on an edge can be claimed by two tets
    // (seen: 3 such centres here, the full assessment then gives it to the last). Allow 8 voxels of 512 mm^3.
    EXPECT_NEAR(full.total_error_volume_mm3, report.iterations.back().total_error_volume_mm3, 8 * 512.0);
    EXPECT_EQ(full.voxels_inside, coarse_head().voxel_count()); // the box holds every voxel centre
    const MeshCheckReport check = check_mesh(mesh);
    EXPECT_TRUE(check.ok()) << (check.problems.empty() ? "" : check.problems.front());
    for (std::size_t i = 1; i < report.iterations.size(); ++i)
        EXPECT_LT(report.iterations[i].reassessed_tets, report.iterations[i].tets)
            << "round " << i << " reassessed everything";
}

TEST(RefineDelaunay, StopsAtTheNodeBudgetAndAtTheTarget)
{
    RefineReport budget;
    const TetMesh capped = refine(coarse_head(), nullptr, {.max_nodes = 400}, {}, &budget);
    EXPECT_EQ(budget.stop_reason, "node budget");
    EXPECT_LE(capped.vertices.size(), 400u);
    RefineReport start;
    refine(coarse_head(), nullptr, {.max_iterations = 0}, {}, &start);
    ASSERT_EQ(start.iterations.size(), 1u);
    EXPECT_EQ(start.stop_reason, "iteration cap");
    const double target_mm3 = 0.5 * start.iterations[0].total_error_volume_mm3;
    RefineReport target;
    refine(coarse_head(), nullptr, {.target_error_mm3 = target_mm3}, {}, &target);
    EXPECT_EQ(target.stop_reason, "target reached");
    EXPECT_TRUE(target.target_reached);
    EXPECT_LE(target.iterations.back().total_error_volume_mm3, target_mm3);
}

TEST(RefineDelaunay, StopsWhenTheErrorVolumeStalls)
{
    RefineReport report;
    refine(coarse_head(), nullptr, {.max_iterations = 200, .max_stalled_rounds = 1}, {}, &report);
    ASSERT_EQ(report.stop_reason, "stalled");
    const std::size_t n = report.iterations.size();
    ASSERT_GE(n, 2u);
    EXPECT_GE(report.iterations[n - 1].total_error_volume_mm3, report.iterations[n - 2].total_error_volume_mm3);
    for (std::size_t i = 1; i + 1 < n; ++i)
        EXPECT_LT(report.iterations[i].total_error_volume_mm3, report.iterations[i - 1].total_error_volume_mm3)
            << "round " << i;
}

} // namespace
} // namespace tissuemesh::volume

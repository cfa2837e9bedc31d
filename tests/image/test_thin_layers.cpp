// Regression: the one-voxel CSF of the 2 mm sphere head touches itself only through edges and corners in
// places (37 pieces under 6-connectivity, 1 under 26). It must not be called "islands", and removing
// islands must not cut it.
#include <gtest/gtest.h>

#include "image/label_statistics.h"
#include "image/phantom.h"
#include "image/remove_islands.h"

namespace tissuemesh::image {
namespace {

TEST(ThinLayers, DiagonallyConnectedCsfIsNotIslands)
{
    Phantom phantom = make_phantom("spheres4", {.voxel_mm = 2});
    const Label csf = 3;
    const LabelStatistics stats = analyze_labels(phantom.image);
    for (const LabelSummary& summary : stats.labels) {
        if (summary.label != csf) continue;
        EXPECT_GT(summary.components6, 1u) << "the premise: CSF falls apart under 6-connectivity at 2 mm";
        EXPECT_EQ(summary.components26, 1u);
        EXPECT_EQ(summary.islands, 0u);
    }
    const auto before = count_labels(phantom.image).at(csf);
    const PrepReport report = remove_islands(phantom.image, {.min_voxels = 10});
    EXPECT_EQ(count_labels(phantom.image).at(csf), before);
    EXPECT_EQ(report.changed_voxels, 0u);
}

} // namespace
} // namespace tissuemesh::image

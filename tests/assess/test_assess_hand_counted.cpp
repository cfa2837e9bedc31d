// Element assessment on tiny meshes whose voxel counts are counted by hand with rasterize.h's tie rule:
// a centre on a face plane goes to the side the plane's normal points to when its first non-zero
// component is positive, i.e. as if the centre were moved by +(1, e, e^2) in index space.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <numeric>

#include "core/error.h"
#include "tests/support/programs.h"
#include "volume/assess.h"
#include "volume/check_mesh.h"

namespace tissuemesh::volume {
namespace {

/// The corner tet of edge 4 voxels on a grid of `spacing` mm: (0,0,0), 4 along x, y and z.
TetMesh corner_tet(double spacing, Label tissue)
{
    const double s = 4 * spacing;
    return testing::single_tet({{{0, 0, 0}, {s, 0, 0}, {0, s, 0}, {0, 0, s}}}, tissue);
}

/// An image of 6^3 voxels of `spacing` mm: tissue 2 on the plane i == 0, tissue 1 elsewhere.
LabelImage split_image(double spacing)
{
    LabelImage image({6, 6, 6}, {spacing, spacing, spacing}, {0, 0, 0}, identity_matrix(), 1);
    for (std::size_t k = 0; k < 6; ++k)
        for (std::size_t j = 0; j < 6; ++j) image.at(0, j, k) = 2;
    return image;
}

std::uint32_t count_in(const Assessment& a, std::size_t t, Label label)
{
    for (std::size_t b = a.histogram_offsets[t]; b < a.histogram_offsets[t + 1]; ++b)
        if (a.histogram[b].label == label) return a.histogram[b].count;
    return 0;
}

TEST(AssessHandCounted, SingleTetHistogramAndExactErrorVolume)
{
    // The tet holds the integer points with i, j, k >= 0 and i + j + k <= 3 (the tie rule keeps the three
    // axis planes, drops the slanted face): C(6, 3) = 20. On the plane i == 0: j + k <= 3, C(5, 2) = 10.
    const double spacing = 0.5;
    const Assessment a = assess_elements(corner_tet(spacing, 1), split_image(spacing));
    EXPECT_EQ(a.voxels_inside, 20u);
    EXPECT_EQ(a.voxel_count[0], 20u);
    EXPECT_EQ(count_in(a, 0, 1), 10u);
    EXPECT_EQ(count_in(a, 0, 2), 10u);
    EXPECT_EQ(a.histogram_offsets[1] - a.histogram_offsets[0], 2u) << "bins only for present tissues";
    // 10 voxels of 0.125 mm^3 are not of tissue 1: exactly 1.25 mm^3 (binary-exact products).
    EXPECT_EQ(a.error_volume_mm3[0], 1.25);
    EXPECT_EQ(a.total_error_volume_mm3, 1.25);
    EXPECT_EQ(a.sampled_tets, 0u);
    EXPECT_NEAR(a.volume_mm3[0], 8.0 / 6.0, 1e-12); // (2 mm)^3 / 6
}

TEST(AssessHandCounted, PriorityWeightsFlipAFiftyFiftyTet)
{
    const double spacing = 0.5;
    const LabelImage image = split_image(spacing);
    // 10 voxels of each tissue: a tie goes to the tet's current tissue.
    EXPECT_EQ(assess_elements(corner_tet(spacing, 1), image).majority[0], 1);
    EXPECT_EQ(assess_elements(corner_tet(spacing, 2), image).majority[0], 2);
    // Weight 1.5 on tissue 2 (15 > 10) flips a tet of tissue 1; the error against the majority is then 10 voxels.
    const Assessment weighted = assess_elements(corner_tet(spacing, 1), image, {.priority = {{2, 1.5}}});
    EXPECT_EQ(weighted.majority[0], 2);
    EXPECT_EQ(weighted.majority_error_volume_mm3[0], 1.25);
    // A weight below 1 on tissue 2 gives it up even for a tet of tissue 2.
    EXPECT_EQ(assess_elements(corner_tet(spacing, 2), image, {.priority = {{2, 0.9}}}).majority[0], 1);
}

TEST(AssessHandCounted, KuhnCubeCountsPerTetAndPerTissue)
{
    // Cube of 2 mm on 0.5 mm voxels: centres at index 0..3 along each axis are inside (faces at index 0
    // kept, at index 4 dropped): 64. Tet (a, b, c) holds x_a >= x_b >= x_c; a tie x_a == x_b stays in it
    // when a < b (the +(1, e, e^2) move grows lower axes more), so a pair with a > b is strict. With s
    // strict pairs the count is the number of such triples in 0..3: C(6 - s, 3) = 20, 10 or 4.
    const TetMesh cube = testing::kuhn_cube(2.0);
    const auto& orders = testing::kuhn_axis_orders;
    LabelImage image({7, 7, 7}, {0.5, 0.5, 0.5});
    for (std::size_t k = 0; k < 4; ++k)
        for (std::size_t j = 0; j < 4; ++j)
            for (std::size_t i = 0; i < 4; ++i) image.at(i, j, k) = i == 3 ? 2 : 1;
    const Assessment a = assess_elements(cube, image);
    const int choose3[] = {20, 10, 4};
    std::uint32_t sum = 0, tissue2 = 0;
    for (std::size_t t = 0; t < 6; ++t) {
        const int strict = (orders[t][0] > orders[t][1]) + (orders[t][1] > orders[t][2]);
        EXPECT_EQ(a.voxel_count[t], static_cast<std::uint32_t>(choose3[strict])) << "tet " << t;
        sum += a.voxel_count[t], tissue2 += count_in(a, t, 2);
    }
    EXPECT_EQ(sum, 64u);
    EXPECT_EQ(a.voxels_inside, 64u);
    // Tet x >= y >= z on the plane i == 3: y >= z in 0..3, 10 points of tissue 2 and 10 of tissue 1.
    EXPECT_EQ(count_in(a, 0, 2), 10u);
    EXPECT_EQ(count_in(a, 0, 1), 10u);
    // Tissue 2 fills the plane i == 3 of the cube: 16 voxels, all misclassified in tets of tissue 1.
    EXPECT_EQ(tissue2, 16u);
    EXPECT_EQ(a.total_error_volume_mm3, 16 * 0.125);
    EXPECT_EQ(a.tissues.at(2).image_voxels, 16u);
    EXPECT_EQ(a.tissues.at(1).agreeing_voxels, 48u);
    EXPECT_DOUBLE_EQ(a.tissues.at(1).dice, 2.0 * 48 / (48 + 64));
    EXPECT_EQ(a.tissues.at(2).dice, 0.0);
    EXPECT_NEAR(a.tissues.at(1).volume_error_mm3, 8.0 - 48 * 0.125, 1e-12);
    const MeshCheckReport check = check_mesh(cube, &image);
    EXPECT_DOUBLE_EQ(a.tissues.at(1).dice, check.tissues.at(1).dice);
    // Kuhn tets: smallest dihedral 45 deg, as check_mesh's own test states.
    for (std::size_t t = 0; t < 6; ++t) EXPECT_NEAR(a.min_dihedral_deg[t], 45.0, 1e-9);
}

TEST(AssessHandCounted, TetSmallerThanAVoxelIsSampled)
{
    // A 0.3 mm tet near voxel (10, 10, 10) on a 1 mm grid holds no centre; all five samples round to that
    // voxel, which is the only one of tissue 3.
    const TetMesh mesh =
        testing::single_tet({{{10.1, 10.1, 10.1}, {10.4, 10.1, 10.1}, {10.1, 10.4, 10.1}, {10.1, 10.1, 10.4}}});
    LabelImage image({20, 20, 20}, {1, 1, 1}, {0, 0, 0}, identity_matrix(), 1);
    image.at(10, 10, 10) = 3;
    const Assessment a = assess_elements(mesh, image);
    EXPECT_EQ(a.voxel_count[0], 0u);
    EXPECT_EQ(a.sampled[0], 1);
    EXPECT_EQ(a.sampled_tets, 1u);
    EXPECT_EQ(a.majority[0], 3);
    EXPECT_EQ(count_in(a, 0, 3), 5u);
    // Every sample disagrees with tissue 1: the estimate is the whole tet; the exact voxel totals hold nothing.
    EXPECT_DOUBLE_EQ(a.error_volume_mm3[0], a.volume_mm3[0]);
    EXPECT_EQ(a.total_error_volume_mm3, 0.0);
    EXPECT_DOUBLE_EQ(a.sampled_error_volume_mm3, a.volume_mm3[0]);
    EXPECT_GT(a.quality_key[0], 0.0);

    // The same through permuted axes and a shifted origin: world = origin + (j, k, i), so voxel (10, 11, 12)
    // has its centre at world (11.5, 12.5, 10.5) and the tet moved there samples it.
    LabelImage turned({20, 20, 20}, {1, 1, 1}, {0.5, 0.5, 0.5}, {0, 1, 0, 0, 0, 1, 1, 0, 0}, 1);
    turned.at(10, 11, 12) = 3;
    TetMesh moved = mesh;
    for (Vec3& v : moved.vertices) v = v + Vec3{1.5, 2.5, 0.5};
    const Assessment b = assess_elements(moved, turned);
    EXPECT_EQ(b.sampled[0], 1);
    EXPECT_EQ(b.majority[0], 3);
}

TEST(AssessHandCounted, RegularTetShapeAndQualityKeyOrder)
{
    // A regular tet (alternate cube corners) free of error has key 0; a flat sliver of error-free voxels sorts
    // before it (its shape term is positive); a tet with misclassified voxels sorts first.
    TetMesh mesh;
    mesh.vertices = {{0, 0, 0}, {2, 2, 0}, {2, 0, 2}, {0, 2, 2}, {5, 0, 0}, {9, 0, 0}, {5, 4, 0}, {7, 2, 0.3}};
    mesh.tets = {{0, 1, 2, 3}, {4, 5, 6, 7}};
    mesh.tet_labels = {1, 1};
    testing::orient_positively(mesh);
    LabelImage image({12, 6, 6}, {1, 1, 1}, {0, 0, 0}, identity_matrix(), 1);
    const Assessment clean = assess_elements(mesh, image);
    EXPECT_NEAR(clean.aspect_ratio[0], 1.0, 1e-12);
    EXPECT_NEAR(clean.radius_edge_ratio[0], std::sqrt(6.0) / 4.0, 1e-12);
    EXPECT_NEAR(clean.quality_key[0], 0.0, 1e-12);
    EXPECT_GT(clean.quality_key[1], 0.0);
    EXPECT_EQ(clean.worst_first, (std::vector<std::uint32_t>{1, 0}));
    image.at(1, 1, 1) = 2; // inside the regular tet (its centroid)
    const Assessment dirty = assess_elements(mesh, image, {.shape_weight = 0.0});
    EXPECT_EQ(dirty.error_volume_mm3[0], 1.0);
    EXPECT_EQ(dirty.quality_key[0], 1.0) << "one misclassified voxel, shape weight 0";
    EXPECT_EQ(dirty.worst_first.front(), 0u);
}

TEST(AssessHandCounted, BadOptionsAndInputsThrow)
{
    const LabelImage image = split_image(1.0);
    EXPECT_THROW(assess_elements(corner_tet(1.0, 1), image, {.priority = {{2, 0.0}}}), InputError);
    EXPECT_THROW(assess_elements(corner_tet(1.0, 1), LabelImage{}), InputError);
    TetMesh dangling = corner_tet(1.0, 1);
    dangling.tets[0][3] = 9;
    EXPECT_THROW(assess_elements(dangling, image), InputError);
}

} // namespace
} // namespace tissuemesh::volume

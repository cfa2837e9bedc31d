// Node placement: geometric centres, and the material-change search finding a known tissue boundary.
#include <gtest/gtest.h>

#include "volume/detail/refine_placement.h"

namespace tissuemesh::volume::detail {
namespace {

/// 10^3 voxels of 1 mm, tissue 1 from i = 5 on: the voxel cells change tissue at x = 4.5 mm.
LabelImage half_and_half()
{
    LabelImage image({10, 10, 10}, {1, 1, 1});
    for (std::size_t k = 0; k < 10; ++k)
        for (std::size_t j = 0; j < 10; ++j)
            for (std::size_t i = 5; i < 10; ++i) image.at(i, j, k) = 1;
    return image;
}

const std::array<Vec3, 4> corners{Vec3{2, 2, 2}, Vec3{8, 2, 2}, Vec3{2, 8, 2}, Vec3{2, 2, 8}};

TEST(RefinePlacement, GeometricCentres)
{
    const LabelImage image = half_and_half();
    EXPECT_EQ(place_node(image, corners, Placement::centroid, 0, false), (Vec3{3.5, 3.5, 3.5}));
    // Longest edges are the three of length 6 sqrt 2; the first found is (8,2,2)-(2,8,2).
    EXPECT_EQ(place_node(image, corners, Placement::longest_edge, 0, false), (Vec3{5, 5, 2}));
    // The corner tet's inscribed sphere touches the three axis planes: its centre has equal coordinates r + 2,
    // r = 3 V / area = 3 * 36 / (3 * 18 + 18 sqrt 3) = 1.268 mm.
    const Vec3 in = place_node(image, corners, Placement::incentre, 0, false);
    const double r = 108.0 / (54.0 + 18.0 * std::sqrt(3.0));
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(in[a], 2 + r, 1e-12);
}

TEST(RefinePlacement, MaterialChangeLandsOnTheTissueBoundary)
{
    const LabelImage image = half_and_half();
    // Half-edges: changes at x = 4.5 on three edges; the one farthest from the corners is on (8,2,2)-(2,8,2).
    const Vec3 edge = place_node(image, corners, Placement::material_half_edges, 0, false);
    EXPECT_NEAR(edge[0], 4.5, 1.0 / 64);         // quarter-voxel steps bisected 4 times
    EXPECT_NEAR(edge[0] + edge[1], 10.0, 1e-12); // on the edge
    EXPECT_EQ(edge[2], 2.0);
    // From the centroid (3.5, 3.5, 3.5) only the ray towards (8,2,2) changes tissue.
    const Vec3 ray = place_node(image, corners, Placement::material_centroid, 0, false);
    EXPECT_NEAR(ray[0], 4.5, 1.0 / 64);
    EXPECT_NEAR(ray[1], ray[2], 1e-12);
    // Constrained mode pulls the node off the faces: every barycentric weight >= 0.05.
    const Vec3 inside = place_node(image, corners, Placement::material_half_edges, 0, true);
    EXPECT_GE(inside[2], 2 + 0.05 * 6 - 1e-12);
    EXPECT_GE(12 - inside[0] - inside[1] - inside[2], 0.05 * 6 - 1e-9);
}

TEST(RefinePlacement, NoChangeFallsBackToTheCentroid)
{
    const LabelImage image({10, 10, 10}, {1, 1, 1}, {0, 0, 0}, identity_matrix(), 3);
    EXPECT_EQ(place_node(image, corners, Placement::material_half_edges, 0, false), (Vec3{3.5, 3.5, 3.5}));
    EXPECT_EQ(voxel_label_at(image, {-0.6, 0, 0}, 7), 7); // outside: the background given
    EXPECT_EQ(voxel_label_at(image, {-0.4, 0, 0}, 7), 3);
}

} // namespace
} // namespace tissuemesh::volume::detail

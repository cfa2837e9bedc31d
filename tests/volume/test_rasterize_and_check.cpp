#include <algorithm>
#include <array>
#include <gtest/gtest.h>

#include "tests/support/programs.h"
#include "volume/check_mesh.h"
#include "volume/rasterize.h"

namespace tissuemesh::volume {
namespace {

std::size_t claimed(const std::vector<std::int32_t>& owner)
{
    return static_cast<std::size_t>(std::count_if(owner.begin(), owner.end(), [](std::int32_t t) { return t >= 0; }));
}

TEST(Rasterize, SingleTetHoldsHandCountedCentres)
{
    // Tet (0,0,0) (4,0,0) (0,4,0) (0,0,4) on a unit grid: the tie rule moves a centre by +(1, e, e^2), so
    // centres on the three axis planes count and those on the slanted face x + y + z = 4 do not: the
    // non-negative integer points with x + y + z <= 3, C(6, 3) = 20 of them.
    const TetMesh mesh = testing::single_tet({{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 4}}});
    const LabelImage image({6, 6, 6}, {1, 1, 1});
    EXPECT_EQ(claimed(rasterize_tets(mesh, image)), 20u);
}

TEST(Rasterize, CubeOfSixTetsClaimsEveryCentreExactlyOnce)
{
    // 5^3 centres lie in the closed cube [0,4]^3; the rule keeps the faces x, y, z = 0 and drops x, y, z = 4,
    // so 4^3 = 64 are inside, each claimed by exactly one of the six tets although most lie on shared
    // faces, edges or the diagonal.
    const TetMesh cube = testing::kuhn_cube(4);
    const LabelImage image({7, 7, 7}, {1, 1, 1});
    std::size_t total = 0;
    for (std::size_t t = 0; t < cube.tets.size(); ++t) {
        TetMesh single = cube;
        single.tets = {cube.tets[t]};
        single.tet_labels = {1};
        total += claimed(rasterize_tets(single, image));
    }
    EXPECT_EQ(total, 64u);
    EXPECT_EQ(claimed(rasterize_tets(cube, image)), 64u);
}

TEST(Rasterize, HonoursSpacingOriginAndDirection)
{
    // The same cube seen through an image with 2 mm voxels, shifted origin and permuted axes: still the
    // same number of centres (the cube is 8 mm, grid 2 mm: 4^3 = 64 half-open cells).
    const TetMesh cube = testing::kuhn_cube(8);
    const Mat3 direction{0, 1, 0, 0, 0, 1, 1, 0, 0};
    const LabelImage image({7, 7, 7}, {2, 2, 2}, {-2, -2, -2}, direction);
    const std::size_t count = claimed(rasterize_tets(cube, image));
    EXPECT_EQ(count, 64u);
}

TEST(CheckMesh, CubeIsConformingWithExactVolumeAndDice)
{
    const TetMesh cube = testing::kuhn_cube(4);
    LabelImage image({6, 6, 6}, {1, 1, 1});
    for (std::size_t k = 0; k < 4; ++k)
        for (std::size_t j = 0; j < 4; ++j)
            for (std::size_t i = 0; i < 4; ++i) image.at(i, j, k) = 1;
    const MeshCheckReport report = check_mesh(cube, &image);
    EXPECT_TRUE(report.ok()) << (report.problems.empty() ? "" : report.problems.front());
    EXPECT_NEAR(report.tissues.at(1).volume_mm3, 64.0, 1e-12);
    EXPECT_EQ(report.tissues.at(1).components, 1u);
    EXPECT_DOUBLE_EQ(report.tissues.at(1).dice, 1.0);
    // Kuhn tets: the smallest dihedral angle is 45 deg, the largest 90 deg (exact for this shape).
    EXPECT_NEAR(report.quality.min_dihedral_deg, 45.0, 1e-9);
    EXPECT_NEAR(report.quality.max_dihedral_deg, 90.0, 1e-9);
}

TEST(CheckMesh, FindsInvertedMissingAndUnmarkedFaces)
{
    TetMesh cube = testing::kuhn_cube(4);
    std::swap(cube.tets[0][0], cube.tets[0][1]);
    EXPECT_EQ(check_mesh(cube).inverted_tets, 1u);

    // Four nodes 1e-12 mm off one plane: positive volume, but flat (and not counted as inverted).
    TetMesh flat;
    flat.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0.5, 1e-12}};
    flat.tets = {{0, 1, 2, 3}};
    flat.tet_labels = {1};
    const MeshCheckReport flat_report = check_mesh(flat);
    EXPECT_EQ(flat_report.flat_tets, 1u);
    EXPECT_EQ(flat_report.inverted_tets, 0u);
    EXPECT_FALSE(flat_report.ok());
    EXPECT_EQ(check_mesh(testing::kuhn_cube(4)).flat_tets, 0u);

    TetMesh doubled = testing::kuhn_cube(4);
    doubled.tets.push_back(doubled.tets[0]);
    doubled.tet_labels.push_back(1);
    EXPECT_EQ(check_mesh(doubled).nonconforming_faces, 4u) << "each face of the repeated tet has 3 users";

    TetMesh loose = testing::kuhn_cube(4);
    loose.vertices.push_back({9, 9, 9});
    EXPECT_EQ(check_mesh(loose).unused_nodes, 1u);

    TetMesh two_tissues = testing::kuhn_cube(4);
    two_tissues.tet_labels[0] = 2;
    const MeshCheckReport report = check_mesh(two_tissues);
    EXPECT_GT(report.unmarked_interfaces, 0u);
    EXPECT_FALSE(report.ok());
}

TEST(CheckMesh, FindsAnOuterBoundaryThatPassesThroughItself)
{
    // Two positive tets with no node in common: apart, the mesh is fit; with the second pushed into the first,
    // no tet is inverted and every face has one tet, but the outer boundary crosses itself and the tets overlap.
    TetMesh apart;
    apart.vertices = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}, {3, 3, 3}, {5, 3, 3}, {3, 5, 3}, {3, 3, 5}};
    apart.tets = {{0, 1, 2, 3}, {4, 5, 6, 7}};
    apart.tet_labels = {1, 1};
    const MeshCheckReport fine = check_mesh(apart);
    EXPECT_EQ(fine.boundary_crossings, 0u);
    EXPECT_TRUE(fine.ok()) << (fine.problems.empty() ? "" : fine.problems.front());

    TetMesh folded = apart;
    for (std::size_t v = 4; v < 8; ++v) folded.vertices[v] = folded.vertices[v] - Vec3{2.8, 2.8, 2.8};
    const MeshCheckReport report = check_mesh(folded);
    EXPECT_EQ(report.inverted_tets + report.flat_tets + report.nonconforming_faces + report.open_boundary_edges, 0u);
    EXPECT_GT(report.boundary_crossings, 0u);
    EXPECT_FALSE(report.ok());
    ASSERT_FALSE(report.problems.empty());
    EXPECT_NE(report.problems.front().find("passes through itself"), std::string::npos) << report.problems.front();

    // Two tets sharing one node meet only there: not a crossing.
    TetMesh touching;
    touching.vertices = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}, {2, 0, 4}, {0, 2, 4}, {0, 0, 4}};
    touching.tets = {{0, 1, 2, 3}, {3, 4, 5, 6}};
    touching.tet_labels = {1, 1};
    const MeshCheckReport touching_report = check_mesh(touching);
    EXPECT_EQ(touching_report.boundary_crossings, 0u);
    EXPECT_TRUE(touching_report.ok()) << (touching_report.problems.empty() ? "" : touching_report.problems.front());
}

} // namespace
} // namespace tissuemesh::volume

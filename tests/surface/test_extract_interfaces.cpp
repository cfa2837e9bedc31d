#include <cmath>
#include <functional>
#include <gtest/gtest.h>
#include <random>

#include "core/error.h"
#include "surface/check_complex.h"
#include "surface/extract_interfaces.h"
#include "tests/surface/complex_checks.h"

namespace tissuemesh {
namespace {

using testing::make_image;
using testing::random_image;

using surface::extract_interfaces;
using testing::invariant_failures;
using testing::tissue_facts;
using testing::voxel_components;

LabelImage ball(int n, double radius, Label inside)
{
    const double c = (n - 1) / 2.0;
    return make_image({static_cast<std::size_t>(n), static_cast<std::size_t>(n), static_cast<std::size_t>(n)},
                      [&](int i, int j, int k) {
                          const double r2 = (i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c);
                          return r2 <= radius * radius ? inside : Label{0};
                      });
}

/// The tests' own invariant checks, and the project's checker (CGAL exact predicates) as a second opinion.
void expect_invariants(const LabelImage& image, bool exact_intersections = true)
{
    const InterfaceComplex complex = extract_interfaces(image);
    EXPECT_EQ(invariant_failures(image, complex, 0, exact_intersections), "");
    const surface::CheckReport report = surface::check_complex(complex);
    EXPECT_TRUE(report.ok()) << (report.first_error() ? report.first_error()->description : "");
}

TEST(ExtractInterfaces, SingleVoxelIsAClosedOctahedron)
{
    const LabelImage image = make_image({1, 1, 1}, [](int, int, int) { return Label{5}; });
    const InterfaceComplex complex = extract_interfaces(image);
    expect_invariants(image);
    const testing::TissueSurfaceFacts facts = tissue_facts(complex, 5);
    EXPECT_EQ(facts.components, 1u);
    // Midpoints of the 14 Freudenthal edges around the voxel; the region is the convex hull of those
    // midpoints, which is not a cube: its volume is a fixed fraction of the voxel, measured here.
    EXPECT_GT(facts.volume_mm3, 0.0);
    EXPECT_LT(facts.volume_mm3, 1.0);
    for (const LabelPair& side : complex.sides) EXPECT_EQ(side.from, 5) << "background is always `to`";
}

TEST(ExtractInterfaces, BallIsClosedAndDoesNotIntersect) { expect_invariants(ball(9, 3.6, 1)); }

TEST(ExtractInterfaces, TwoTouchingBoxes)
{
    const LabelImage image = make_image({6, 4, 4}, [](int i, int, int) { return Label(i < 3 ? 1 : 2); });
    const InterfaceComplex complex = extract_interfaces(image);
    EXPECT_EQ(invariant_failures(image, complex, 0, true), "");
    // Away from the junction with the background (which lies in the padding cubes, y or z outside
    // [0, 3]), the 1|2 interface is the plane i = 2.5 between the boxes; from = 2 (larger label), to = 1.
    double planar_area = 0;
    for (std::size_t t = 0; t < complex.triangle_count(); ++t) {
        if (complex.sides[t].to != 1 || complex.sides[t].from != 2) continue;
        bool interior = true;
        for (const std::uint32_t v : complex.triangles[t])
            for (const int axis : {1, 2})
                interior = interior && complex.vertices[v][axis] >= 0 && complex.vertices[v][axis] <= 3;
        if (!interior) continue;
        const Triangle& tri = complex.triangles[t];
        for (const std::uint32_t v : tri) EXPECT_DOUBLE_EQ(complex.vertices[v][0], 2.5);
        const Vec3 normal = cross(complex.vertices[tri[1]] - complex.vertices[tri[0]],
                                  complex.vertices[tri[2]] - complex.vertices[tri[0]]);
        EXPECT_LT(normal[0], 0) << "normal points from 2 (larger i) into 1";
        planar_area += 0.5 * norm(normal);
    }
    // The plane part covers the 3 x 3 mm square between the voxel centres 0..3 exactly.
    EXPECT_NEAR(planar_area, 9.0, 1e-12);
}

TEST(ExtractInterfaces, DiagonalNeighboursFollowTheFreudenthalRule)
{
    // (0,0,0) and (1,1,1): neighbours along the decomposition's main diagonal -> one component.
    const LabelImage along = make_image({2, 2, 2}, [](int i, int j, int k) { return Label(i == j && j == k); });
    EXPECT_EQ(voxel_components(along, 1, 0, false), 1u);
    EXPECT_EQ(tissue_facts(extract_interfaces(along), 1).components, 1u);
    expect_invariants(along);
    // (1,0,0) and (0,1,1): the other diagonal is not a Freudenthal edge -> two separate surfaces.
    const LabelImage across = make_image({2, 2, 2}, [](int i, int j, int k) {
        return Label((i == 1 && j == 0 && k == 0) || (i == 0 && j == 1 && k == 1));
    });
    EXPECT_EQ(voxel_components(across, 1, 0, false), 2u);
    EXPECT_EQ(tissue_facts(extract_interfaces(across), 1).components, 2u);
    expect_invariants(across);
    // Face diagonals: (0,0) and (1,1) in a slice are connected, (1,0) and (0,1) are not.
    const LabelImage face = make_image({2, 2, 1}, [](int i, int j, int) { return Label(i == j ? 1 : 2); });
    EXPECT_EQ(tissue_facts(extract_interfaces(face), 1).components, 1u);
    EXPECT_EQ(tissue_facts(extract_interfaces(face), 2).components, 2u);
    expect_invariants(face);
}

TEST(ExtractInterfaces, OneVoxelShellHasInnerAndOuterSurface)
{
    const LabelImage image = make_image({7, 7, 7}, [](int i, int j, int k) {
        const int d = std::max({std::abs(i - 3), std::abs(j - 3), std::abs(k - 3)});
        return Label(d == 2 ? 1 : (d < 2 ? 2 : 0));
    });
    expect_invariants(image);
    EXPECT_EQ(tissue_facts(extract_interfaces(image), 1).components, 2u) << "outer and inner side of the shell";
    // The same shell with nothing inside: the cavity is background, a second background component.
    const LabelImage hollow = make_image({7, 7, 7}, [](int i, int j, int k) {
        return Label(std::max({std::abs(i - 3), std::abs(j - 3), std::abs(k - 3)}) == 2 ? 1 : 0);
    });
    expect_invariants(hollow);
    EXPECT_EQ(tissue_facts(extract_interfaces(hollow), 0).components, 2u);
}

TEST(ExtractInterfaces, ThreeTissuesMeetAlongALineAndEightAtAPoint)
{
    const LabelImage line = make_image({4, 4, 3}, [](int i, int j, int) { return Label(i < 2 ? 1 : (j < 2 ? 2 : 3)); });
    expect_invariants(line);
    const LabelImage point =
        make_image({4, 4, 4}, [](int i, int j, int k) { return Label(1 + (i >= 2) + 2 * (j >= 2) + 4 * (k >= 2)); });
    expect_invariants(point);
}

TEST(ExtractInterfaces, RandomTwoByTwoByTwoConfigurationsWithThreeOrMoreLabels)
{
    // Fixed seed: 1000 random 2x2x2 label cubes over labels 0..4 with at least 3 distinct labels
    // (padding adds the background around them, so all cube configurations of the padded grid occur).
    std::mt19937 random(20261122);
    int tested = 0;
    while (tested < 1000) {
        const LabelImage image = random_image({2, 2, 2}, random, 4);
        if (count_labels(image).size() < 3) continue;
        ++tested;
        const InterfaceComplex complex = extract_interfaces(image);
        const std::string failures = invariant_failures(image, complex, 0, true);
        ASSERT_EQ(failures, "") << "configuration " << tested;
        ASSERT_TRUE(surface::check_complex(complex).ok()) << "configuration " << tested;
    }
}

TEST(ExtractInterfaces, RandomLabelFieldsKeepEveryInvariant)
{
    std::mt19937 random(7);
    for (int trial = 0; trial < 60; ++trial) {
        const LabelImage image = random_image({4, 4, 4}, random, 3);
        const InterfaceComplex complex = extract_interfaces(image);
        ASSERT_EQ(invariant_failures(image, complex, 0, true), "") << "trial " << trial;
        const surface::CheckReport report = surface::check_complex(complex);
        ASSERT_TRUE(report.ok()) << "trial " << trial << ": "
                                 << (report.first_error() ? report.first_error()->description : "");
    }
}

TEST(ExtractInterfaces, HonoursSpacingOriginAndMirroredDirection)
{
    // A mirrored, permuted direction (determinant -1) and anisotropic spacing: the world volume of the
    // ball's surface must still be positive (outward normals) and close to its voxel volume.
    const LabelImage unit = ball(11, 4.2, 3);
    LabelImage image(unit.dims(), {0.5, 1.0, 2.0}, {-7, 3, 11}, {0, 1, 0, 1, 0, 0, 0, 0, 1});
    image.labels() = unit.labels();
    const InterfaceComplex complex = extract_interfaces(image);
    EXPECT_EQ(invariant_failures(image, complex, 0, false), "");
    const InterfaceComplex plain = extract_interfaces(unit);
    EXPECT_NEAR(tissue_facts(complex, 3).volume_mm3, tissue_facts(plain, 3).volume_mm3 * image.voxel_volume_mm3(),
                1e-9 * tissue_facts(plain, 3).volume_mm3)
        << "world volume = index volume * voxel volume";
    const Vec3 first = complex.vertices.front();
    const Vec3 index = image.world_to_index(first);
    for (const double c : index) EXPECT_NEAR(c * 12, std::round(c * 12), 1e-9) << "dual points on the 1/12 lattice";
}

} // namespace
} // namespace tissuemesh

namespace tissuemesh {
namespace {

LabelImage three_blocks()
{
    LabelImage image({6, 2, 2}, {1, 1, 1});
    for (std::size_t k = 0; k < 2; ++k)
        for (std::size_t j = 0; j < 2; ++j)
            for (std::size_t i = 0; i < 6; ++i) image.at(i, j, k) = static_cast<Label>(1 + i / 2);
    return image;
}

TEST(ComplexChecks, DetectBrokenComplexes)
{
    // The tests' checks must be able to fail: break a good complex in three ways.
    const LabelImage image = make_image({2, 2, 2}, [](int i, int j, int k) { return Label(1 + (i + j + k) % 3); });
    const InterfaceComplex good = surface::extract_interfaces(image);
    ASSERT_EQ(invariant_failures(image, good, 0, true), "");
    InterfaceComplex flipped = good;
    std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
    EXPECT_GT(testing::tissue_facts(flipped, good.sides[0].from).bad_edges, 0u);
    InterfaceComplex doubled = good;
    doubled.add_triangle(good.triangles[5], good.sides[5]);
    EXPECT_EQ(testing::duplicate_triangles(doubled), 1u);
    // Push one vertex far along the x axis: its triangles now cut through others.
    InterfaceComplex moved = good;
    const std::uint32_t v = moved.triangles[0][0];
    moved.vertices[v][0] += moved.vertices[v][0] > 0.5 ? -1.5 : 1.5;
    EXPECT_GT(testing::intersecting_pairs(moved), 0u);
}

TEST(ExtractInterfaces, TissueSelectionMergesOthersIntoBackground)
{
    const InterfaceComplex complex = surface::extract_interfaces(three_blocks(), {.tissues = {1, 3}});
    for (const LabelPair& side : complex.sides) {
        EXPECT_NE(side.from, 2);
        EXPECT_EQ(side.to, 0) << "1 and 3 are apart once 2 is background";
    }
    // Background 2: the blocks 1 and 3 touch only label 2, which is now `to`.
    const InterfaceComplex inside = surface::extract_interfaces(three_blocks(), {.tissues = {1, 3}, .background = 2});
    for (const LabelPair& side : inside.sides) EXPECT_EQ(side.to, 2);
}

TEST(ExtractInterfaces, RejectsBadOptionsWithOneLineMessages)
{
    const auto expect_input_error = [](const LabelImage& image, const surface::ExtractOptions& options,
                                       const std::string& hint) {
        try {
            surface::extract_interfaces(image, options);
            ADD_FAILURE() << "accepted: " << hint;
        } catch (const InputError& error) {
            EXPECT_NE(std::string(error.what()).find(hint), std::string::npos) << error.what();
        }
    };
    expect_input_error(three_blocks(), {.tissues = {9}}, "tissue 9 does not occur");
    expect_input_error(three_blocks(), {.tissues = {1, 2}, .background = 2}, "also the background");
    expect_input_error(LabelImage({3, 3, 3}, {1, 1, 1}), {}, "only background");
    expect_input_error(LabelImage(), {}, "no voxels");
}

} // namespace
} // namespace tissuemesh

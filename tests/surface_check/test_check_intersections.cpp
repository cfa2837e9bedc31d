// Intersections: triangles may meet only at the vertices and edges they share.
#include <cmath>
#include <gtest/gtest.h>

#include "surface/check_complex.h"
#include "tests/support/complexes.h"
#include "tests/surface_check/defects_of_kind.h"

namespace tissuemesh {
namespace {

using surface::check_complex;
using surface::CheckReport;
using surface::Defect;
using surface::DefectKind;
using testing::of_kind;

std::size_t intersections(const CheckReport& report)
{
    return report.count(DefectKind::self_intersection) + report.count(DefectKind::patch_intersection);
}

/// Two triangles (pairs 1|0 and 2|0) built from `points` by index, nothing else.
InterfaceComplex two_triangles(std::vector<Vec3> points, const Triangle& a, const Triangle& b)
{
    InterfaceComplex complex;
    complex.vertices = std::move(points);
    complex.add_triangle(a, {1, 0});
    complex.add_triangle(b, {2, 0});
    return complex;
}

TEST(CheckComplexIntersections, InterpenetratingCubesIntersectInsideTheOverlap)
{
    InterfaceComplex complex;
    testing::add_box(complex, {0, 0, 0}, {2, 2, 2}, 1, 0);
    testing::add_box(complex, {1, 1, 1}, {3, 3, 3}, 2, 0);
    complex.names = {{0, "air"}, {1, "scalp"}, {2, "skull"}};
    const CheckReport report = check_complex(complex);
    EXPECT_FALSE(report.ok());
    EXPECT_GT(report.count(DefectKind::patch_intersection), 0u);
    EXPECT_EQ(report.count(DefectKind::self_intersection), 0u);
    // Each tissue is closed on its own: the intersection is the only problem.
    EXPECT_TRUE(report.tissues.at(1).closed && report.tissues.at(2).closed);
    for (const Defect& defect : report.defects) {
        ASSERT_EQ(defect.kind, DefectKind::patch_intersection) << defect.description;
        EXPECT_EQ(defect.tissues, (std::vector<Label>{0, 1, 2}));
        EXPECT_NE(defect.description.find("scalp|air triangle"), std::string::npos) << defect.description;
        EXPECT_NE(defect.description.find("skull|air triangle"), std::string::npos) << defect.description;
        // The surfaces cross only where the boxes overlap, [1, 2]^3 (the location is a rounded
        // construction: allow 1e-9 mm).
        for (int axis = 0; axis < 3; ++axis) {
            EXPECT_GE(defect.location_mm[axis], 1 - 1e-9) << defect.description;
            EXPECT_LE(defect.location_mm[axis], 2 + 1e-9) << defect.description;
        }
    }
}

TEST(CheckComplexIntersections, VertexPushedThroughTheOppositeFaceIsASelfIntersection)
{
    // A unit cube whose corner (0, 0, 0) is moved out through the face x = 1: the triangles around that
    // corner now cross the face, all within the one patch between skull and air.
    InterfaceComplex complex = testing::voxel_faces({.labels = {1}});
    complex.names = {{0, "air"}, {1, "skull"}};
    complex.vertices[0] = {2, 0.5, 0.5};
    const CheckReport report = check_complex(complex);
    EXPECT_FALSE(report.ok());
    EXPECT_GT(report.count(DefectKind::self_intersection), 0u);
    EXPECT_EQ(report.count(DefectKind::patch_intersection), 0u);
    const Defect& defect = *of_kind(report, DefectKind::self_intersection).front();
    EXPECT_EQ(defect.tissues, (std::vector<Label>{0, 1}));
    // The moved corner's triangles lie on the cube's lower faces, named air|skull (behind|in front).
    EXPECT_NE(defect.description.find("self-intersection between air|skull triangle"), std::string::npos)
        << defect.description;
    // Some crossing is located on the pierced face x = 1 (a rounded construction: 1e-9 mm).
    bool on_pierced_face = false;
    for (const Defect& found : report.defects)
        on_pierced_face = on_pierced_face || std::abs(found.location_mm[0] - 1.0) < 1e-9;
    EXPECT_TRUE(on_pierced_face);
}

TEST(CheckComplexIntersections, TrianglesSharingOnlyAVertexAreFine)
{
    // Non-coplanar, and coplanar with the wedges at the shared vertex on opposite sides.
    EXPECT_EQ(intersections(check_complex(
                  two_triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 1}, {-1, 0, 1}}, {0, 1, 2}, {0, 3, 4}))),
              0u);
    EXPECT_EQ(intersections(check_complex(
                  two_triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}}, {0, 1, 2}, {0, 3, 4}))),
              0u);
}

TEST(CheckComplexIntersections, TrianglesSharingOnlyAnEdgeAreFine)
{
    // A fold (non-coplanar) and a flat pair (coplanar, third vertices on opposite sides).
    EXPECT_EQ(intersections(check_complex(
                  two_triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, -1, 0.3}}, {0, 1, 2}, {1, 0, 3}))),
              0u);
    EXPECT_EQ(intersections(
                  check_complex(two_triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, -1, 0}}, {0, 1, 2}, {1, 0, 3}))),
              0u);
}

TEST(CheckComplexIntersections, SharedVertexWithCrossingNearItIsAnIntersection)
{
    // The second triangle pierces the first along a segment starting at their shared vertex.
    const CheckReport pierced = check_complex(
        two_triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.2, 1}, {0.2, 0.2, -1}}, {0, 1, 2}, {0, 3, 4}));
    EXPECT_EQ(pierced.count(DefectKind::patch_intersection), 1u);
    // Coplanar, overlapping wedges at the shared vertex.
    const CheckReport overlapping =
        check_complex(two_triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5, 2, 0}}, {0, 1, 2}, {0, 3, 4}));
    EXPECT_EQ(overlapping.count(DefectKind::patch_intersection), 1u);
}

TEST(CheckComplexIntersections, SharedEdgeFoldedFlatOntoItselfIsAnIntersection)
{
    // Coplanar, third vertices on the same side of the shared edge: the triangles overlap.
    const CheckReport report =
        check_complex(two_triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.6, 0.8, 0}}, {0, 1, 2}, {1, 0, 3}));
    EXPECT_EQ(report.count(DefectKind::patch_intersection), 1u);
}

TEST(CheckComplexIntersections, CoplanarOverlapWithoutSharedVerticesIsAnIntersection)
{
    const CheckReport report = check_complex(two_triangles(
        {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, 0}, {3, 0.5, 0}, {0.5, 3, 0}}, {0, 1, 2}, {3, 4, 5}));
    ASSERT_EQ(report.count(DefectKind::patch_intersection), 1u);
    const Defect& defect = *of_kind(report, DefectKind::patch_intersection).front();
    // The overlap is the triangle (0.5, 0.5), (1.5, 0.5), (0.5, 1.5) in z = 0; its centroid is reported.
    EXPECT_NEAR(defect.location_mm[0], 5.0 / 6.0, 1e-9);
    EXPECT_NEAR(defect.location_mm[1], 5.0 / 6.0, 1e-9);
    EXPECT_NEAR(defect.location_mm[2], 0.0, 1e-12);
}

TEST(CheckComplexIntersections, CoplanarContactsAreDecidedExactly)
{
    // All in the plane x + y + z = 3 (not axis-aligned, so the 2D test runs on a projection).
    const auto plane = [](double u, double v) { return Vec3{u, v, 3 - u - v}; };
    const auto meets = [&](std::vector<Vec3> points) {
        return intersections(check_complex(two_triangles(std::move(points), {0, 1, 2}, {3, 4, 5})));
    };
    // Contained: the small triangle inside the big one.
    EXPECT_EQ(meets({plane(0, 0), plane(4, 0), plane(0, 4), plane(1, 1), plane(2, 1), plane(1, 2)}), 1u);
    // A corner of the second exactly on the first one's long edge u + v = 4 (a T-junction).
    EXPECT_EQ(meets({plane(0, 0), plane(4, 0), plane(0, 4), plane(2, 2), plane(4, 2), plane(2, 4)}), 1u);
    // The same, moved off that edge by one binary step of 1/1024 mm: apart.
    const double gap = 1.0 / 1024;
    EXPECT_EQ(meets({plane(0, 0), plane(4, 0), plane(0, 4), plane(2 + gap, 2), plane(4, 2), plane(2 + gap, 4)}), 0u);
}

TEST(CheckComplexIntersections, TouchingWithoutSharingTheVertexIsAnIntersection)
{
    // The second triangle's corner lies on the first one's interior, but is a different vertex.
    const CheckReport report = check_complex(two_triangles(
        {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, 0}, {0.5, 0.5, 1}, {1, 0.5, 1}}, {0, 1, 2}, {3, 4, 5}));
    EXPECT_EQ(report.count(DefectKind::patch_intersection), 1u);
}

TEST(CheckComplexIntersections, CanBeSkipped)
{
    InterfaceComplex complex;
    testing::add_box(complex, {0, 0, 0}, {2, 2, 2}, 1, 0);
    testing::add_box(complex, {1, 1, 1}, {3, 3, 3}, 2, 0);
    const CheckReport report = check_complex(complex, {.check_intersections = false});
    EXPECT_FALSE(report.intersections_checked);
    EXPECT_TRUE(report.ok()); // what was checked passed; the caller knows intersections were not
}

} // namespace
} // namespace tissuemesh

// Broken complexes: each defect is found, of the right kind, naming the right tissues and place.
#include <gtest/gtest.h>

#include "core/error.h"
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

/// A named unit cube of skull (1) in air (0), 12 triangles, vertices on the lattice {0, 1}^3.
InterfaceComplex skull_cube()
{
    InterfaceComplex complex = testing::voxel_faces({.labels = {1}});
    complex.names = {{0, "air"}, {1, "skull"}};
    return complex;
}

bool mentions(const Defect& defect, const std::string& text)
{
    return defect.description.find(text) != std::string::npos;
}

TEST(CheckComplexDefects, HoleGivesOpenEdgesOnBothSides)
{
    InterfaceComplex complex = skull_cube();
    complex.triangles.pop_back();
    complex.sides.pop_back();
    const CheckReport report = check_complex(complex);
    EXPECT_FALSE(report.ok());
    // The missing triangle's three edges, once in skull's surface and once in air's.
    EXPECT_EQ(report.count(DefectKind::open_edge), 6u);
    EXPECT_FALSE(report.tissues.at(1).closed);
    EXPECT_EQ(report.tissues.at(1).open_edges, 3u);
    EXPECT_EQ(report.tissues.at(0).open_edges, 3u);
    EXPECT_TRUE(report.tissues.at(1).oriented);
    const auto open = of_kind(report, DefectKind::open_edge);
    ASSERT_EQ(open.size(), 6u);
    EXPECT_EQ(open[0]->tissues, (std::vector<Label>{0, 1}));
    EXPECT_TRUE(mentions(*open[0], "open edge")) << open[0]->description;
    // The patch is named behind|in front: air|skull on the cube's lower faces, skull|air on the upper.
    EXPECT_TRUE(mentions(*open[0], "air|skull triangle") || mentions(*open[0], "skull|air triangle"))
        << open[0]->description;
    EXPECT_TRUE(mentions(*open[0], " mm")) << open[0]->description;
    EXPECT_EQ(report.count(DefectKind::self_intersection) + report.count(DefectKind::patch_intersection), 0u);
}

TEST(CheckComplexDefects, FlippedTriangleGivesOrientationConflicts)
{
    InterfaceComplex complex = skull_cube();
    testing::flip_triangle(complex, 5);
    const CheckReport report = check_complex(complex);
    EXPECT_FALSE(report.ok());
    EXPECT_EQ(report.count(DefectKind::orientation_conflict), 6u); // 3 edges, in both tissues' surfaces
    EXPECT_EQ(report.count(DefectKind::open_edge), 0u);
    EXPECT_TRUE(report.tissues.at(1).closed);
    EXPECT_FALSE(report.tissues.at(1).oriented);
    EXPECT_EQ(report.tissues.at(1).orientation_conflicts, 3u);
    const auto conflicts = of_kind(report, DefectKind::orientation_conflict);
    ASSERT_FALSE(conflicts.empty());
    bool names_flipped = false;
    for (const Defect* defect : conflicts)
        names_flipped = names_flipped || std::count(defect->triangles.begin(), defect->triangles.end(), 5u) > 0;
    EXPECT_TRUE(names_flipped);
}

TEST(CheckComplexDefects, DuplicateTriangleIsAnError)
{
    InterfaceComplex complex = skull_cube();
    const Triangle copy{complex.triangles[3][1], complex.triangles[3][2], complex.triangles[3][0]}; // rotated
    complex.add_triangle(copy, complex.sides[3]);
    const CheckReport report = check_complex(complex);
    EXPECT_FALSE(report.ok());
    ASSERT_EQ(report.count(DefectKind::duplicate_triangle), 1u);
    const Defect& defect = *of_kind(report, DefectKind::duplicate_triangle).front();
    EXPECT_EQ(defect.triangles, (std::vector<std::uint32_t>{3, 12}));
    EXPECT_EQ(defect.tissues, (std::vector<Label>{0, 1}));
    EXPECT_TRUE(mentions(defect, "skull|air triangle 3 and skull|air triangle 12")) << defect.description;
}

TEST(CheckComplexDefects, DegenerateTrianglesAreErrors)
{
    InterfaceComplex complex = skull_cube();
    testing::add_lone_triangle(complex, {10, 0, 0}, {11, 1, 1}, {13, 3, 3}, {1, 0}); // collinear
    complex.add_triangle({0, 1, 1}, {1, 0});                                         // repeated vertex
    const CheckReport report = check_complex(complex);
    EXPECT_FALSE(report.ok());
    const auto degenerate = of_kind(report, DefectKind::degenerate_triangle);
    ASSERT_EQ(degenerate.size(), 2u);
    EXPECT_TRUE(mentions(*degenerate[0], "collinear")) << degenerate[0]->description;
    EXPECT_EQ(degenerate[0]->triangles, (std::vector<std::uint32_t>{12}));
    EXPECT_TRUE(mentions(*degenerate[1], "repeated vertex")) << degenerate[1]->description;
    EXPECT_EQ(report.count(DefectKind::needle_triangle), 0u); // degenerate, not merely thin
}

TEST(CheckComplexDefects, DuplicateVerticesAreErrors)
{
    InterfaceComplex complex = skull_cube();
    // Give two triangles at the corner (1, 1, 1) their own copy of that vertex.
    const std::uint32_t corner = 7;
    complex.vertices.push_back(complex.vertices[corner]);
    int replaced = 0;
    for (Triangle& tri : complex.triangles)
        for (std::uint32_t& v : tri)
            if (v == corner && replaced < 2) v = 8, ++replaced;
    const CheckReport report = check_complex(complex);
    EXPECT_FALSE(report.ok());
    ASSERT_EQ(report.count(DefectKind::duplicate_vertex), 1u);
    const Defect& defect = *of_kind(report, DefectKind::duplicate_vertex).front();
    EXPECT_EQ(defect.location_mm, (Vec3{1, 1, 1}));
    EXPECT_TRUE(mentions(defect, "vertices 7 and 8")) << defect.description;
    EXPECT_FALSE(report.tissues.at(1).closed); // by index the surface is torn at the copy
}

TEST(CheckComplexDefects, CopiedVerticesAreNotAlsoReportedAsIntersections)
{
    // Two triangles of a unit square whose shared edge uses copies of its end points: the copies are
    // the defect; geometrically the triangles meet properly along that edge.
    InterfaceComplex complex;
    complex.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    complex.add_triangle({0, 1, 2}, {1, 0});
    complex.add_triangle({3, 5, 4}, {1, 0});
    const CheckReport report = check_complex(complex);
    EXPECT_EQ(report.count(DefectKind::duplicate_vertex), 2u);
    EXPECT_EQ(report.count(DefectKind::patch_intersection) + report.count(DefectKind::self_intersection), 0u);
    EXPECT_EQ(report.count(DefectKind::duplicate_triangle), 0u);
}

TEST(CheckComplexDefects, TissueTouchingItselfAlongAnEdgeIsNonManifold)
{
    // Two skull voxels meeting only along the vertical edge x = y = 1 (a checkerboard).
    const InterfaceComplex complex = testing::voxel_faces({.nx = 2, .ny = 2, .labels = {1, 0, 0, 1}});
    const CheckReport report = check_complex(complex);
    EXPECT_FALSE(report.ok());
    // The edge is used by 4 triangles of skull's and of air's surface.
    EXPECT_EQ(report.count(DefectKind::non_manifold_edge), 2u);
    EXPECT_EQ(report.tissues.at(1).non_manifold_edges, 1u);
    EXPECT_TRUE(report.tissues.at(1).closed);
    EXPECT_EQ(report.count(DefectKind::patch_intersection) + report.count(DefectKind::self_intersection), 0u);
}

TEST(CheckComplexDefects, InsideOutTissueIsInverted)
{
    InterfaceComplex complex = skull_cube();
    for (LabelPair& pair : complex.sides) std::swap(pair.from, pair.to);
    const CheckReport report = check_complex(complex);
    EXPECT_FALSE(report.ok());
    EXPECT_EQ(report.count(DefectKind::inverted_tissue), 2u); // skull encloses -1 mm^3, air +1 mm^3
    EXPECT_NEAR(report.tissues.at(1).volume_mm3, -1.0, 1e-12);
}

TEST(CheckComplexDefects, NeedlesAreWarningsOnly)
{
    InterfaceComplex complex;
    // A long thin tetrahedron: the faces meeting at (100, 0, 0) have angles of atan(1/100) = 0.57 deg there.
    complex.vertices = {{0, 0, 0}, {100, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    complex.add_triangle({0, 2, 1}, {1, 0});
    complex.add_triangle({0, 1, 3}, {1, 0});
    complex.add_triangle({0, 3, 2}, {1, 0});
    complex.add_triangle({1, 2, 3}, {1, 0});
    const CheckReport report = check_complex(complex);
    EXPECT_TRUE(report.ok());
    EXPECT_EQ(report.count(DefectKind::needle_triangle), 3u);
    EXPECT_EQ(report.warning_count(), 3u);
    EXPECT_EQ(report.error_count(), 0u);
    EXPECT_EQ(check_complex(complex, {.needle_angle_deg = 0.5}).count(DefectKind::needle_triangle), 0u);
}

TEST(CheckComplexDefects, StoredDefectsAreCappedButCountsExact)
{
    InterfaceComplex complex = testing::icosphere(2, 5.0, {0, 0, 0});
    for (std::size_t t = 0; t < complex.triangles.size(); t += 2) complex.sides[t] = {0, 1}; // half inverted
    const CheckReport report = check_complex(complex, {.max_defects_per_kind = 3});
    EXPECT_GT(report.count(DefectKind::orientation_conflict), 3u);
    EXPECT_EQ(of_kind(report, DefectKind::orientation_conflict).size(), 3u);
}

TEST(CheckComplexDefects, RequireFitThrowsWithFirstDefectAndHint)
{
    InterfaceComplex complex = skull_cube();
    complex.triangles.pop_back();
    complex.sides.pop_back();
    try {
        surface::require_fit_for_tetrahedralization(complex, "head.ply");
        FAIL() << "an open surface was accepted";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("head.ply: not fit for tetrahedralization: 6 defects"), std::string::npos) << message;
        EXPECT_NE(message.find("open edge"), std::string::npos) << message;
        EXPECT_NE(message.find("re-extract it with tm-extract"), std::string::npos) << message;
    }
    EXPECT_NO_THROW(surface::require_fit_for_tetrahedralization(skull_cube(), "head.ply"));
    EXPECT_THROW(surface::require_fit_for_tetrahedralization(InterfaceComplex{}, "empty.ply"), InputError);
}

TEST(CheckComplexDefects, BadIndicesAreInputErrors)
{
    InterfaceComplex complex = skull_cube();
    complex.triangles[0][1] = 99;
    EXPECT_THROW(check_complex(complex), InputError);
    EXPECT_THROW(check_complex(skull_cube(), {.needle_angle_deg = -1}), InputError);
}

} // namespace
} // namespace tissuemesh

// Complexes fit for tetrahedralization: the checker accepts them and measures them exactly.
#include <cmath>
#include <gtest/gtest.h>

#include "surface/check_complex.h"
#include "tests/support/complexes.h"

namespace tissuemesh {
namespace {

using surface::check_complex;
using surface::CheckReport;
using testing::voxel_faces;
using testing::VoxelBlock;

std::string defects_of(const CheckReport& report)
{
    std::string text;
    for (const surface::Defect& defect : report.defects) text += defect.description + "\n";
    return text;
}

TEST(CheckComplex, AcceptsTetrahedronWithExactVolume)
{
    InterfaceComplex complex;
    testing::add_tetrahedron(complex, {10, -3, 2}, 3.0, 1, 0);
    const CheckReport report = check_complex(complex);
    EXPECT_TRUE(report.ok()) << defects_of(report);
    EXPECT_TRUE(report.intersections_checked);
    ASSERT_EQ(report.tissues.size(), 2u);
    const surface::TissueCheck& tissue = report.tissues.at(1);
    EXPECT_TRUE(tissue.closed);
    EXPECT_TRUE(tissue.oriented);
    EXPECT_EQ(tissue.components, 1u);
    EXPECT_EQ(tissue.triangles, 4u);
    // 3^3 / 6 = 4.5 mm^3; a handful of roundings of small integers.
    EXPECT_NEAR(tissue.volume_mm3, 4.5, 1e-12);
    EXPECT_NEAR(report.tissues.at(0).volume_mm3, -4.5, 1e-12);
    EXPECT_EQ(report.vertices, 4u);
    EXPECT_EQ(report.edges, 6u);
    EXPECT_EQ(report.junction_edges, 0u);
    EXPECT_TRUE(report.defects.empty());
}

TEST(CheckComplex, AcceptsCubeWithExactVolume)
{
    const InterfaceComplex complex = voxel_faces({.labels = {5}, .size_mm = 2.0, .origin_mm = {-7, 1, 30}});
    const CheckReport report = check_complex(complex);
    EXPECT_TRUE(report.ok()) << defects_of(report);
    EXPECT_EQ(report.triangles, 12u);
    EXPECT_EQ(report.edges, 18u); // 12 cube edges and 6 face diagonals
    EXPECT_NEAR(report.tissues.at(5).volume_mm3, 8.0, 1e-12);
    EXPECT_NEAR(report.tissues.at(0).volume_mm3, -8.0, 1e-12);
}

TEST(CheckComplex, AcceptsNestedCubesWithExactVolumes)
{
    // A 3x3x3 block of tissue 1 whose centre voxel is tissue 2: a cube inside a cube.
    VoxelBlock block{.nx = 3, .ny = 3, .nz = 3, .labels = std::vector<Label>(27, 1), .size_mm = 0.5};
    block.labels[13] = 2;
    InterfaceComplex complex = testing::voxel_faces(block);
    complex.names = {{0, "air"}, {1, "skull"}, {2, "brain"}};
    const CheckReport report = check_complex(complex);
    EXPECT_TRUE(report.ok()) << defects_of(report);
    ASSERT_EQ(report.tissues.size(), 3u);
    const double voxel = 0.125; // 0.5^3 mm^3, exact in binary
    EXPECT_NEAR(report.tissues.at(2).volume_mm3, 1 * voxel, 1e-12);
    EXPECT_NEAR(report.tissues.at(1).volume_mm3, 26 * voxel, 1e-12);
    EXPECT_NEAR(report.tissues.at(0).volume_mm3, -27 * voxel, 1e-12);
    // Tissue 1's surface has an outer and an inner sheet.
    EXPECT_EQ(report.tissues.at(1).components, 2u);
    EXPECT_EQ(report.tissues.at(2).components, 1u);
    EXPECT_EQ(report.tissues.at(0).components, 1u);
    EXPECT_EQ(report.junction_edges, 0u);
}

TEST(CheckComplex, AcceptsCubesSharingAFaceWithJunctionEdges)
{
    const InterfaceComplex complex = voxel_faces({.nx = 2, .labels = {1, 2}});
    const CheckReport report = check_complex(complex);
    EXPECT_TRUE(report.ok()) << defects_of(report);
    // The shared unit square's four sides are where tissues 0, 1 and 2 meet, three triangles each.
    EXPECT_EQ(report.junction_edges, 4u);
    EXPECT_NEAR(report.tissues.at(1).volume_mm3, 1.0, 1e-12);
    EXPECT_NEAR(report.tissues.at(2).volume_mm3, 1.0, 1e-12);
    EXPECT_NEAR(report.tissues.at(0).volume_mm3, -2.0, 1e-12);
    EXPECT_EQ(report.tissues.at(1).triangles, 12u);
}

TEST(CheckComplex, AcceptsThreeTissuesMeetingAtACurveAndBackgroundVolumeBalances)
{
    // A 2x2 block: tissues 1 and 2 side by side, an L of tissue 3; the central vertical edge is a
    // junction of 1, 2 and 3, the outer vertical edges between them junctions with the background.
    const InterfaceComplex complex = voxel_faces({.nx = 2, .ny = 2, .labels = {1, 2, 3, 3}, .size_mm = 1.5});
    const CheckReport report = check_complex(complex);
    EXPECT_TRUE(report.ok()) << defects_of(report);
    const double voxel = 1.5 * 1.5 * 1.5;
    EXPECT_NEAR(report.tissues.at(1).volume_mm3, 1 * voxel, 1e-12);
    EXPECT_NEAR(report.tissues.at(2).volume_mm3, 1 * voxel, 1e-12);
    EXPECT_NEAR(report.tissues.at(3).volume_mm3, 2 * voxel, 1e-12);
    // The background's outward surface faces into the block: minus everything enclosed.
    EXPECT_NEAR(report.tissues.at(0).volume_mm3, -4 * voxel, 1e-12);
    // Where three tissues meet: 4 vertical unit edges (the centre, and where 1|2, 1|3, 2|3 meet the
    // outside) and 3 in each of the top and bottom faces (along the 1|2, 1|3 and 2|3 walls).
    EXPECT_EQ(report.junction_edges, 10u);
}

TEST(CheckComplex, AcceptsTetrahedraTouchingAtOneVertex)
{
    InterfaceComplex complex;
    testing::add_tetrahedron(complex, {0, 0, 0}, 1.0, 1, 0);
    testing::add_tetrahedron(complex, {1, 0, 0}, 1.0, 2, 0);
    // Make the second tetrahedron use the first one's vertex (1, 0, 0) by index: they share it exactly.
    for (Triangle& tri : complex.triangles)
        for (std::uint32_t& v : tri)
            if (v == 4) v = 1;
    const CheckReport report = check_complex(complex);
    EXPECT_TRUE(report.ok()) << defects_of(report);
    EXPECT_EQ(report.vertices, 7u);
}

TEST(CheckComplex, IcosphereVolumeIsThePolyhedronVolume)
{
    const Vec3 centre{10, -20, 30};
    const double radius = 7.0;
    const InterfaceComplex complex = testing::icosphere(3, radius, centre);
    const CheckReport report = check_complex(complex);
    EXPECT_TRUE(report.ok()) << defects_of(report);
    // Independent evaluation: a fan of tetrahedra from the sphere's centre, and the inradius.
    double fan = 0;
    double inradius = radius;
    for (const Triangle& t : complex.triangles) {
        const Vec3 a = complex.vertices[t[0]] - centre, b = complex.vertices[t[1]] - centre,
                   c = complex.vertices[t[2]] - centre;
        fan += dot(a, cross(b, c)) / 6.0;
        const Vec3 n = cross(b - a, c - a);
        inradius = std::min(inradius, dot(a, n) / norm(n));
    }
    const double volume = report.tissues.at(1).volume_mm3;
    // Same quantity about a different origin: equal up to rounding of ~1e3 terms of size ~1 mm^3.
    EXPECT_NEAR(volume, fan, 1e-9 * fan);
    const double pi = 3.14159265358979323846;
    EXPECT_LT(volume, 4.0 / 3.0 * pi * radius * radius * radius);       // inscribed in the sphere
    EXPECT_GT(volume, 4.0 / 3.0 * pi * inradius * inradius * inradius); // contains the insphere
    EXPECT_EQ(report.tissues.at(1).components, 1u);
}

} // namespace
} // namespace tissuemesh

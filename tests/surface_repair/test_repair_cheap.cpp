// repair(): the cheap, unambiguous fixes (coincident vertices, repeated, zero-area and flipped triangles),
// what it refuses (holes, ambiguous doubles), and that a valid complex comes back unchanged.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "image/phantom.h"
#include "surface/check_complex.h"
#include "surface/extract_interfaces.h"
#include "surface/repair.h"
#include "tests/support/complexes.h"

namespace tissuemesh {
namespace {

using testing::icosphere;

double volume_of(const InterfaceComplex& complex, Label tissue)
{
    return surface::check_complex(complex, {.check_intersections = false}).tissues.at(tissue).volume_mm3;
}

void expect_fit(const InterfaceComplex& complex)
{
    const surface::CheckReport check = surface::check_complex(complex);
    EXPECT_TRUE(check.ok()) << (check.first_error() ? check.first_error()->description : "");
}

std::size_t count_kind(const surface::RepairReport& report, surface::RepairKind kind)
{
    return static_cast<std::size_t>(std::count_if(report.actions.begin(), report.actions.end(),
                                                  [&](const surface::RepairAction& a) { return a.kind == kind; }));
}

TEST(RepairCheap, ValidComplexComesBackUnchanged)
{
    InterfaceComplex complex = surface::extract_interfaces(image::make_phantom("junction", {.voxel_mm = 4.0}).image);
    const InterfaceComplex original = complex;
    const surface::RepairReport report = surface::repair(complex, {.gap_mm = 0.1});
    EXPECT_FALSE(report.changed());
    EXPECT_TRUE(report.actions.empty());
    EXPECT_EQ(complex.triangles.size(), original.triangles.size());
    EXPECT_EQ(complex.vertices, original.vertices);
    expect_fit(complex);
}

TEST(RepairCheap, TriangleSoupIsWelded)
{
    // Every triangle with its own three vertices (as STL stores them): every tissue is open until welded.
    const InterfaceComplex sphere = icosphere(2, 10.0, {0, 0, 0});
    InterfaceComplex soup;
    for (std::size_t t = 0; t < sphere.triangles.size(); ++t) {
        const auto base = static_cast<std::uint32_t>(soup.vertices.size());
        for (const std::uint32_t v : sphere.triangles[t]) soup.vertices.push_back(sphere.vertices[v]);
        soup.add_triangle({base, base + 1, base + 2}, sphere.sides[t]);
    }
    ASSERT_FALSE(surface::check_complex(soup).ok());
    const surface::RepairReport report = surface::repair(soup);
    EXPECT_EQ(report.merged_vertices, 3 * sphere.triangles.size() - sphere.vertices.size());
    EXPECT_EQ(soup.triangle_count(), sphere.triangle_count());
    EXPECT_EQ(soup.vertex_count(), sphere.vertex_count());
    EXPECT_NEAR(volume_of(soup, 1), volume_of(sphere, 1), 1e-9);
    expect_fit(soup);
}

TEST(RepairCheap, RepeatsAndRepeatedVertexTrianglesAreDropped)
{
    InterfaceComplex complex = icosphere(1, 10.0, {0, 0, 0});
    const std::size_t triangles = complex.triangle_count();
    const Triangle t = complex.triangles[3];
    complex.add_triangle(t, complex.sides[3]);                                              // the same triangle again
    complex.add_triangle({t[0], t[2], t[1]}, {complex.sides[3].to, complex.sides[3].from}); // the same, other way round
    complex.add_triangle({t[0], t[0], t[1]}, {1, 0});                                       // a repeated vertex
    const surface::RepairReport report = surface::repair(complex);
    EXPECT_EQ(report.removed_duplicates, 2u);
    EXPECT_EQ(report.removed_degenerate, 1u);
    EXPECT_EQ(count_kind(report, surface::RepairKind::removed_duplicate), 2u);
    EXPECT_EQ(complex.triangle_count(), triangles);
    expect_fit(complex);
}

TEST(RepairCheap, ZeroAreaTriangleIsCollapsed)
{
    // Split edge ab of triangles abc and bad at its midpoint m on one side only, and close the gap with the
    // zero-area triangle abm: closed, but degenerate.
    InterfaceComplex complex = icosphere(2, 10.0, {0, 0, 0});
    const InterfaceComplex original = complex;
    const Triangle abc = complex.triangles[0];
    const std::uint32_t a = abc[0], b = abc[1], c = abc[2];
    const auto m = static_cast<std::uint32_t>(complex.vertices.size());
    complex.vertices.push_back(0.5 * (complex.vertices[a] + complex.vertices[b]));
    complex.triangles[0] = {a, m, c};
    complex.add_triangle({m, b, c}, {1, 0});
    complex.add_triangle({a, b, m}, {1, 0});
    const surface::CheckReport broken = surface::check_complex(complex);
    ASSERT_EQ(broken.count(surface::DefectKind::degenerate_triangle), 1u);
    const surface::RepairReport report = surface::repair(complex);
    EXPECT_EQ(report.collapsed_degenerate, 1u);
    EXPECT_EQ(complex.triangle_count(), original.triangle_count());
    EXPECT_NEAR(volume_of(complex, 1), volume_of(original, 1), 1e-9);
    expect_fit(complex);
    ASSERT_FALSE(report.actions.empty());
    EXPECT_NE(report.actions.front().description.find("collapsed zero-area 1|0 triangle"), std::string::npos)
        << report.actions.front().description;
}

TEST(RepairCheap, FlippedTrianglesAreTurned)
{
    InterfaceComplex complex = surface::extract_interfaces(image::make_phantom("junction", {.voxel_mm = 4.0}).image);
    const double volume = volume_of(complex, 2);
    for (const std::size_t t : {std::size_t{10}, std::size_t{500}, complex.triangles.size() - 1})
        testing::flip_triangle(complex, t);
    ASSERT_GT(surface::check_complex(complex).count(surface::DefectKind::orientation_conflict), 0u);
    const surface::RepairReport report = surface::repair(complex);
    EXPECT_EQ(report.flipped_triangles, 3u);
    EXPECT_NEAR(volume_of(complex, 2), volume, 1e-9 * volume);
    expect_fit(complex);
}

TEST(RepairCheap, RefusesHolesWithTheDefectAndWhatToDo)
{
    InterfaceComplex complex = icosphere(2, 10.0, {0, 0, 0});
    complex.triangles.pop_back();
    complex.sides.pop_back();
    try {
        surface::repair(complex);
        FAIL() << "a hole cannot be repaired";
    } catch (const AlgorithmError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("6 open-edge defects"), std::string::npos) << message;
        EXPECT_NE(message.find("re-extract the interfaces from the label image with tm-extract"), std::string::npos)
            << message;
    }
}

TEST(RepairCheap, AmbiguousDoublesStay)
{
    // The same triangle wound both ways with the same tissues: which side is tissue 1 is not known.
    InterfaceComplex complex = icosphere(1, 10.0, {0, 0, 0});
    const Triangle t = complex.triangles[0];
    complex.add_triangle({t[0], t[2], t[1]}, complex.sides[0]);
    EXPECT_THROW(surface::repair(complex), AlgorithmError);
}

TEST(RepairCheap, RejectsBadOptions)
{
    InterfaceComplex complex = icosphere(0, 1.0, {0, 0, 0});
    EXPECT_THROW(surface::repair(complex, {.gap_mm = -1}), InputError);
    EXPECT_THROW(surface::repair(complex, {.max_depth_voxels = 0}), InputError);
    InterfaceComplex empty;
    EXPECT_THROW(surface::repair(empty), InputError);
}

} // namespace
} // namespace tissuemesh

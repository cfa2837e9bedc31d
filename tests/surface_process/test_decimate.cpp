// decimate(): fewer triangles, within the distance bound, and a complex that still passes the checker
// with the same pieces per tissue; junction curves collapse only along themselves.
#include <gtest/gtest.h>
#include <algorithm>
#include <iostream>

#include "core/error.h"
#include "image/phantom.h"
#include "surface/check_complex.h"
#include "surface/decimate.h"
#include "surface/detail/layer_sizing.h"
#include "surface/extract_interfaces.h"
#include "tests/support/phantom_distance.h"

namespace tissuemesh {
namespace {

void check_decimation(const std::string& name, double voxel_mm, const surface::DecimateOptions& options,
                      double min_reduction)
{
    const image::Phantom phantom = image::make_phantom(name, {.voxel_mm = voxel_mm});
    InterfaceComplex complex = surface::extract_interfaces(phantom.image);
    const surface::CheckReport before = surface::check_complex(complex);
    ASSERT_TRUE(before.ok());
    const testing::DistanceFigures raw = testing::phantom_distances(phantom, complex);
    const surface::DecimateReport report = surface::decimate(complex, options);
    const testing::DistanceFigures after_figures = testing::phantom_distances(phantom, complex);
    const surface::CheckReport after = surface::check_complex(complex);
    std::cout << "[ figures  ] " << name << " at " << voxel_mm << " mm: " << report.triangles_before << " -> "
              << report.triangles_after << " triangles (" << report.collapses << " collapses, refused "
              << report.refused_by_distance << " by distance, " << report.refused_by_checks << " by checks: topology "
              << report.refused_topology << " shape " << report.refused_shape << " fold " << report.refused_fold
              << " intersection " << report.refused_intersection << " gap " << report.refused_gap
              << "); tracked distance max " << report.max_distance_mm << " mm; vertex distance to the exact "
              << "interfaces max/mean " << raw.max_voxels << "/" << raw.mean_voxels << " -> "
              << after_figures.max_voxels << "/" << after_figures.mean_voxels << " voxel\n";
    EXPECT_TRUE(after.ok()) << (after.first_error() ? after.first_error()->description : "");
    EXPECT_LE(report.max_distance_mm, options.max_distance_mm);
    EXPECT_GE(static_cast<double>(report.triangles_before),
              min_reduction * static_cast<double>(report.triangles_after));
    ASSERT_EQ(after.tissues.size(), before.tissues.size());
    for (const auto& [tissue, facts] : before.tissues) {
        const surface::TissueCheck& now = after.tissues.at(tissue);
        EXPECT_EQ(now.components, facts.components) << "tissue " << tissue;
        // Each input vertex stays within max_distance_mm of the output, so volumes move by about the surface
        // area times that bound at most; 5% holds on these phantoms (figures above).
        EXPECT_NEAR(now.volume_mm3, facts.volume_mm3, 0.05 * std::abs(facts.volume_mm3)) << "tissue " << tissue;
    }
    EXPECT_EQ(after.junction_edges > 0, before.junction_edges > 0) << "junction curves kept";
}

// Raw marching-cubes terraces are creases everywhere: most collapses would fold a triangle by more than
// 20 degrees, so raw input reduces about 3x (smoothed input much more).
TEST(Decimate, JunctionCurvatureMode) { check_decimation("junction", 2.0, {.max_distance_mm = 1.0}, 3); }

TEST(Decimate, ThinShellStaysOnePiece) { check_decimation("thin", 1.0, {.max_distance_mm = 0.5}, 2); }

TEST(Decimate, LongBoxesFlatFacesCollapse) { check_decimation("boxes", 2.0, {.max_distance_mm = 1.0}, 20); }

TEST(Decimate, RefusesCollapsesThatWouldCrossTheOtherSideOfAThinLayer)
{
    // The shell is one voxel (1 mm) thick; a 2 mm distance bound alone would let its two surfaces cross.
    const image::Phantom phantom = image::make_phantom("thin", {.voxel_mm = 1.0});
    InterfaceComplex complex = surface::extract_interfaces(phantom.image);
    const surface::DecimateReport report = surface::decimate(complex, {.max_distance_mm = 2.0});
    std::cout << "[ figures  ] thin, 2 mm bound: " << report.triangles_before << " -> " << report.triangles_after
              << " triangles; refused by intersection " << report.refused_intersection << ", by gap "
              << report.refused_gap << "\n";
    EXPECT_GT(report.refused_intersection + report.refused_gap, 0u);
    const surface::CheckReport after = surface::check_complex(complex);
    EXPECT_TRUE(after.ok()) << (after.first_error() ? after.first_error()->description : "");
}

TEST(Decimate, SizeModeSplitsAndCollapses)
{
    check_decimation("junction", 2.0,
                     {.mode = surface::DecimateMode::size, .max_distance_mm = 1.0, .target_edge_mm = 6.0}, 3);
}

TEST(Decimate, TargetTriangleCountStopsEarly)
{
    const image::Phantom phantom = image::make_phantom("junction", {.voxel_mm = 2.0});
    InterfaceComplex complex = surface::extract_interfaces(phantom.image);
    const std::size_t target = complex.triangle_count() / 2;
    surface::decimate(complex, {.target_triangles = target});
    EXPECT_LE(complex.triangle_count(), target);
    EXPECT_GE(complex.triangle_count() + 4, target) << "stops as soon as it reaches the target";
    EXPECT_TRUE(surface::check_complex(complex).ok());
}

double longest_edge_mm(const InterfaceComplex& complex)
{
    double longest = 0;
    for (const Triangle& t : complex.triangles)
        for (int k = 0; k < 3; ++k)
            longest = std::max(longest, distance(complex.vertices[t[k]], complex.vertices[t[(k + 1) % 3]]));
    return longest;
}

/// The edge bound of curvature mode: unbounded, the flat faces of the boxes end in edges far longer than
/// the bound; bounded, no edge is longer than the bound (the raw edges are all shorter) and the complex
/// still passes the checker.
TEST(Decimate, MaxEdgeBoundsTheEdgesCollapsesLeave)
{
    const image::Phantom phantom = image::make_phantom("boxes", {.voxel_mm = 2.0});
    const InterfaceComplex raw = surface::extract_interfaces(phantom.image);
    constexpr double bound = 5.0;
    ASSERT_LT(longest_edge_mm(raw), bound);
    InterfaceComplex free = raw, bounded = raw;
    surface::decimate(free, {.max_distance_mm = 1.0});
    const surface::DecimateReport report = surface::decimate(bounded, {.max_distance_mm = 1.0, .max_edge_mm = bound});
    std::cout << "[ figures  ] boxes at 2 mm: longest edge " << longest_edge_mm(raw) << " mm raw, "
              << longest_edge_mm(free) << " mm decimated (" << free.triangle_count() << " triangles), "
              << longest_edge_mm(bounded) << " mm with a " << bound << " mm bound (" << bounded.triangle_count()
              << " triangles, " << report.refused_by_length << " collapses refused by it)\n";
    EXPECT_GT(longest_edge_mm(free), 2 * bound);
    EXPECT_LE(longest_edge_mm(bounded), bound);
    EXPECT_GT(report.refused_by_length, 0u);
    EXPECT_LT(bounded.triangle_count(), raw.triangle_count() / 4);
    EXPECT_TRUE(surface::check_complex(bounded).ok());
}

/// The `thin` phantom's shell is one voxel (2 mm) thick. Decimated under a 10 mm edge bound it gets edges far
/// longer than that; with one edge length per mm of thickness (a bound of 4/3 of 2.5 mm there: the sizing's
/// smallest edge is a quarter of the max edge), no collapse leaves an edge longer than 4/3 of the sizing at its
/// midpoint (the extracted edges, all shorter, are kept), and the complex stays valid with the same pieces.
TEST(Decimate, EdgesFollowTheThicknessOfAThinLayer)
{
    const image::Phantom phantom = image::make_phantom("thin", {.voxel_mm = 2.0});
    const InterfaceComplex raw = surface::extract_interfaces(phantom.image);
    const surface::CheckReport before = surface::check_complex(raw);
    const surface::DecimateOptions plain_options{.max_distance_mm = 1, .max_edge_mm = 10, .max_normal_change_deg = 45};
    surface::DecimateOptions sized_options = plain_options;
    sized_options.edge_per_thickness = 1;
    InterfaceComplex plain = raw, sized = raw;
    surface::decimate(plain, plain_options);
    const surface::DecimateReport report = surface::decimate(sized, sized_options);
    const surface::detail::LayerSizing sizing(raw, raw.background,
                                              {.target_edge_mm = 7.5, .edges_per_mm = 1, .min_edge_mm = 2.5});
    double worst = 0; // the longest edge over its bound
    for (const Triangle& t : sized.triangles)
        for (int k = 0; k < 3; ++k) {
            const Vec3 &a = sized.vertices[t[k]], &b = sized.vertices[t[(k + 1) % 3]];
            worst = std::max(worst, distance(a, b) / (4.0 / 3.0 * sizing.at(0.5 * (a + b))));
        }
    std::cout << "[ figures  ] thin 2 mm decimated under a 10 mm edge bound: longest edge " << longest_edge_mm(plain)
              << " mm, " << plain.triangle_count() << " triangles; with one edge per mm of thickness "
              << longest_edge_mm(sized) << " mm, " << sized.triangle_count() << " triangles ("
              << report.refused_by_length << " collapses refused by length), longest edge / its bound " << worst
              << "\n";
    EXPECT_GT(longest_edge_mm(plain), 5.0);
    EXPECT_LE(worst, 1 + 1e-9);
    EXPECT_LT(longest_edge_mm(sized), 0.5 * longest_edge_mm(plain));
    EXPECT_GT(static_cast<double>(sized.triangle_count()), 1.3 * static_cast<double>(plain.triangle_count()));
    EXPECT_LT(sized.triangle_count(), raw.triangle_count() / 2);
    const surface::CheckReport after = surface::check_complex(sized);
    EXPECT_TRUE(after.ok()) << (after.first_error() ? after.first_error()->description : "");
    ASSERT_EQ(after.tissues.size(), before.tissues.size());
    for (const auto& [tissue, facts] : before.tissues)
        EXPECT_EQ(after.tissues.at(tissue).components, facts.components) << "tissue " << tissue;
}

TEST(Decimate, RejectsBadOptions)
{
    InterfaceComplex complex;
    EXPECT_THROW(surface::decimate(complex, {.max_distance_mm = 0}), InputError);
    EXPECT_THROW(surface::decimate(complex, {.mode = surface::DecimateMode::size}), InputError);
    EXPECT_THROW(surface::decimate(complex, {.max_edge_mm = -1}), InputError);
    // Size mode bounds its edges by its target; a second bound there would be silently ignored.
    EXPECT_THROW(
        surface::decimate(complex, {.mode = surface::DecimateMode::size, .max_edge_mm = 3, .target_edge_mm = 2}),
        InputError);
    EXPECT_THROW(surface::decimate(complex, {.slabs = surface::DecimateOptions::max_slabs + 1}), InputError);
    // The thickness bound narrows the max edge: without one it would be silently ignored.
    EXPECT_THROW(surface::decimate(complex, {.edge_per_thickness = 4}), InputError);
    EXPECT_THROW(surface::decimate(complex, {.max_edge_mm = 4, .edge_per_thickness = -1}), InputError);
}

} // namespace
} // namespace tissuemesh

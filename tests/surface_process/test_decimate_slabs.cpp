// decimate() in slabs: each slab is decimated on its own, fenced off from the others, then one pass goes
// over the seams. The result must be as valid as decimating the whole at once, keep the distance bound,
// and come out about as coarse.
#include <gtest/gtest.h>

#include <iostream>
#include <limits>

#include "image/phantom.h"
#include "surface/check_complex.h"
#include "surface/decimate.h"
#include "surface/detail/slabs.h"
#include "surface/extract_interfaces.h"
#include "surface/smooth.h"
#include "tests/support/phantom_distance.h"
#include "tests/support/slab_comparison.h"

namespace tissuemesh {
namespace {

struct Outcome {
    InterfaceComplex complex;
    surface::DecimateReport report;
    surface::CheckReport check;
    testing::DistanceFigures distances;
};

Outcome decimate_in(const image::Phantom& phantom, const InterfaceComplex& smoothed, std::size_t slabs)
{
    Outcome outcome{smoothed, {}, {}, {}};
    outcome.report = surface::decimate(outcome.complex, {.max_distance_mm = 0.5, .slabs = slabs});
    outcome.check = surface::check_complex(outcome.complex);
    outcome.distances = testing::phantom_distances(phantom, outcome.complex);
    return outcome;
}

void compare_slabs_with_whole(const std::string& name, double voxel_mm, std::size_t slabs)
{
    const image::Phantom phantom = image::make_phantom(name, {.voxel_mm = voxel_mm});
    InterfaceComplex smoothed = surface::extract_interfaces(phantom.image);
    surface::smooth(smoothed, phantom.image);
    const surface::CheckReport before = surface::check_complex(smoothed);
    ASSERT_TRUE(before.ok());
    const Outcome whole = decimate_in(phantom, smoothed, 1);
    const Outcome cut = decimate_in(phantom, smoothed, slabs);
    std::cout << "[ figures  ] " << name << " at " << voxel_mm << " mm, " << smoothed.triangle_count()
              << " triangles: whole -> " << whole.report.triangles_after
              << " (distance to the exact interfaces max/mean " << whole.distances.max_voxels << "/"
              << whole.distances.mean_voxels << " voxel), " << cut.report.slabs << " slabs -> "
              << cut.report.triangles_after << " (" << cut.distances.max_voxels << "/" << cut.distances.mean_voxels
              << " voxel)\n";
    EXPECT_EQ(whole.report.slabs, 1u);
    EXPECT_EQ(cut.report.slabs, slabs);
    EXPECT_LE(cut.report.max_distance_mm, 0.5);
    // The collapses differ in their order near the seams, so the counts differ a little (measured: thin -1.5%,
    // junction +3.6%, where 320 000 triangles become 8 000; spheres4 -0.2%; the 1 mm head +0.02%).
    EXPECT_NEAR(static_cast<double>(cut.report.triangles_after), static_cast<double>(whole.report.triangles_after),
                0.05 * static_cast<double>(whole.report.triangles_after));
    // Both keep every input vertex within 0.5 mm of the output, so both stay as close to the exact interfaces
    // as the smoothed input plus that bound; the slabs must not be worse than the whole by a tenth of a voxel.
    EXPECT_LE(cut.distances.max_voxels, whole.distances.max_voxels + 0.1);
    EXPECT_LE(cut.distances.mean_voxels, whole.distances.mean_voxels + 0.01);
    testing::expect_slabs_keep_the_whole(cut.check, whole.check, before);
}

// The thin shell is one voxel thick: across every seam its two sides must stay apart.
TEST(DecimateSlabs, ThinShellInFiveSlabsMatchesTheWhole) { compare_slabs_with_whole("thin", 1.0, 5); }

// Junction curves cross the seams: they must stay shared and collapse only along themselves there too.
TEST(DecimateSlabs, JunctionInFourSlabsMatchesTheWhole) { compare_slabs_with_whole("junction", 1.0, 4); }

TEST(DecimateSlabs, SpheresInEightSlabsMatchTheWhole) { compare_slabs_with_whole("spheres4", 4.0, 8); }

TEST(DecimateSlabs, SlabsOwnEveryTriangleOnceAndHoldWhatReachesThem)
{
    const image::Phantom phantom = image::make_phantom("junction", {.voxel_mm = 2.0});
    const InterfaceComplex complex = surface::extract_interfaces(phantom.image);
    const std::vector<surface::detail::Slab> slabs = surface::detail::cut_into_slabs(complex, 3);
    ASSERT_EQ(slabs.size(), 3u);
    std::vector<int> owners(complex.triangle_count(), 0);
    for (const surface::detail::Slab& slab : slabs) {
        const surface::detail::SlabPiece piece = surface::detail::slab_piece(complex, slab);
        std::vector<char> held(complex.triangle_count(), 0);
        for (std::size_t t = 0; t < piece.from_triangle.size(); ++t) {
            held[piece.from_triangle[t]] = 1;
            for (int k = 0; k < 3; ++k)
                EXPECT_EQ(piece.complex.vertices[piece.complex.triangles[t][k]],
                          complex.vertices[complex.triangles[piece.from_triangle[t]][k]]);
        }
        for (std::uint32_t t = 0; t < complex.triangle_count(); ++t) {
            const auto [from, to] = surface::detail::span(complex, t, slab.axis);
            EXPECT_EQ(held[t] != 0, to >= slab.low && from <= slab.high) << "triangle " << t;
            if (slab.owns(from)) ++owners[t];
        }
        // Each slab owns about a third of the triangles.
        std::size_t owned = 0;
        for (std::uint32_t t = 0; t < complex.triangle_count(); ++t)
            owned += slab.owns(surface::detail::span(complex, t, slab.axis).first) ? 1 : 0;
        const auto all = static_cast<double>(complex.triangle_count());
        EXPECT_NEAR(static_cast<double>(owned), all / 3.0, 0.05 * all);
    }
    for (std::uint32_t t = 0; t < complex.triangle_count(); ++t) EXPECT_EQ(owners[t], 1) << "triangle " << t;
}

// The second round of slabs: each cut of the first lies in the middle of a slab of the second, half a
// first slab from its ends, so the seams the first fences left are decimated away from any fence.
TEST(DecimateSlabs, SlabsBetweenPutEveryCutInTheMiddleOfASlab)
{
    constexpr double infinity = std::numeric_limits<double>::infinity();
    const std::vector<surface::detail::Slab> first{{1, -infinity, 10}, {1, 10, 20}, {1, 20, 40}, {1, 40, infinity}};
    const std::vector<surface::detail::Slab> between = surface::detail::slabs_between(first);
    ASSERT_EQ(between.size(), 3u);
    EXPECT_EQ(between[0].axis, 1);
    EXPECT_EQ(between[0].low, -infinity);
    EXPECT_EQ(between[0].high, 15.0);
    EXPECT_EQ(between[1].low, 15.0);
    EXPECT_EQ(between[1].high, 30.0);
    EXPECT_EQ(between[2].low, 30.0);
    EXPECT_EQ(between[2].high, infinity);
    // Each first cut inside one second slab: 10 in (-inf, 15), 20 in [15, 30), 40 in [30, inf).
    EXPECT_TRUE(between[0].owns(10) && between[1].owns(20) && between[2].owns(40));
    EXPECT_TRUE(surface::detail::slabs_between({first[0], first[3]}).empty());
}

} // namespace
} // namespace tissuemesh

// The surface view of three nested spheres: the cut-away shows every layer, in its colour, at its radius.
#include <cmath>
#include <gtest/gtest.h>

#include "core/error.h"
#include "render/render_surface.h"
#include "render/tissue_colours.h"
#include "tests/support/complexes.h"
#include "tests/support/pictures.h"

namespace tissuemesh {
namespace {

/// Spheres of radius 30, 20, 10 mm around the origin: tissue 1 between 30 and 20, 2 between 20 and 10,
/// 3 inside 10; each sphere's normals point outwards (from the inner tissue to the outer one).
InterfaceComplex nested_spheres()
{
    InterfaceComplex complex;
    const std::array<std::pair<double, LabelPair>, 3> shells{{{30, {1, 0}}, {20, {2, 1}}, {10, {3, 2}}}};
    for (const auto& [radius, pair] : shells) {
        const InterfaceComplex sphere = testing::icosphere(4, radius, {0, 0, 0});
        const auto offset = static_cast<std::uint32_t>(complex.vertices.size());
        complex.vertices.insert(complex.vertices.end(), sphere.vertices.begin(), sphere.vertices.end());
        for (const Triangle& t : sphere.triangles)
            complex.add_triangle({t[0] + offset, t[1] + offset, t[2] + offset}, pair);
    }
    complex.names = {{1, "scalp"}, {2, "skull"}, {3, "brain"}};
    return complex;
}

TEST(SurfaceView, WedgeCutShowsEveryNestedTissue)
{
    const InterfaceComplex complex = nested_spheres();
    render::SurfaceViewReport report;
    const render::Canvas picture =
        render::render_surface(complex, {.width_px = 400, .height_px = 400, .legend = false}, &report);
    EXPECT_GT(report.triangles_cut, 0u);
    EXPECT_EQ(report.triangles_cut + report.triangles_drawn, complex.triangle_count());
    for (const Label label : std::vector<Label>{1, 2, 3})
        EXPECT_GT(testing::count_shaded(picture, render::tissue_colour(label)), 1000u) << "tissue " << label;

    // Without the cut only the outer tissue is seen: the depth buffer hides the inner spheres.
    const render::Canvas whole = render::render_surface(
        complex, {.width_px = 400, .height_px = 400, .cut = render::CutAway::none, .legend = false});
    EXPECT_GT(testing::count_shaded(whole, render::tissue_colour(1)),
              30000u); // a disc of radius 0.95 x 200 / sqrt 3 px
    EXPECT_EQ(testing::count_shaded(whole, render::tissue_colour(2)), 0u);
    EXPECT_EQ(testing::count_shaded(whole, render::tissue_colour(3)), 0u);
}

TEST(SurfaceView, HalfCutSeenHeadOnShowsTheRingsAtTheirRadii)
{
    // Looking along -x at the cut x > 0: the cut face shows flat rings 3 | 2 | 1 out to 10, 20, 30 mm.
    const std::size_t side = 601;
    const render::Canvas picture = render::render_surface(nested_spheres(), {.width_px = side,
                                                                             .height_px = side,
                                                                             .azimuth_deg = 0,
                                                                             .elevation_deg = 0,
                                                                             .cut = render::CutAway::half,
                                                                             .legend = false});
    const long centre = static_cast<long>(side / 2);
    auto edge_of = [&](Label label) { // last pixel to the right of the centre in the tissue's flat colour
        long last = -1;
        for (long x = centre; x < static_cast<long>(side); ++x)
            if (picture.at(static_cast<std::size_t>(x), static_cast<std::size_t>(centre)) ==
                render::tissue_colour(label))
                last = x;
        return static_cast<double>(last - centre);
    };
    const double r3 = edge_of(3), r2 = edge_of(2), r1 = edge_of(1);
    ASSERT_GT(r3, 0);
    // Icosphere facets lie up to 0.2% inside the sphere; a pixel is about 0.3% of the outer radius.
    EXPECT_NEAR(r3 / r1, 1.0 / 3, 0.01);
    EXPECT_NEAR(r2 / r1, 2.0 / 3, 0.01);
    EXPECT_EQ(picture.at(side - 2, side / 2), (render::Rgb{255, 255, 255}));
}

TEST(SurfaceView, RefusesAnEmptyComplexAndUnknownCuts)
{
    EXPECT_THROW(render::render_surface(InterfaceComplex{}), InputError);
    try {
        render::parse_cut_away("slab");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "unknown cut-away \"slab\"; use none, half or wedge");
    }
}

} // namespace
} // namespace tissuemesh

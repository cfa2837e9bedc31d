// The field view of the nested-cubes mesh (4 mm cube, 2 mm inner cube): colours follow the field, the colour
// bar spans its range, tissue outlines are drawn.
#include <gtest/gtest.h>

#include "core/error.h"
#include "render/render_field.h"
#include "tests/io/expect_error.h"
#include "tests/support/programs.h"

namespace tissuemesh {
namespace {

using render::Canvas;
using testing::nested_cubes_mesh;

/// The map position (0..1) of pixel (x, y), or -1 when it is not a colour of the map (white, black, text).
double position_at(const Canvas& picture, std::size_t x, std::size_t y)
{
    const render::Rgb c = picture.at(x, y);
    const double t = render::field_position(c);
    const render::Rgb back = render::field_colour(t);
    for (std::size_t k = 0; k < 3; ++k)
        if (std::abs(back[k] - c[k]) > 2) return -1;
    return t;
}

/// The mean map position over a column of the plot area, ignoring pixels that are not map colours.
double column_mean(const Canvas& picture, std::size_t x)
{
    double sum = 0;
    int n = 0;
    for (std::size_t y = 0; y < picture.height(); ++y)
        if (const double t = position_at(picture, x, y); t >= 0) sum += t, ++n;
    return n > 0 ? sum / n : -1;
}

TEST(FieldView, TheColourMapRisesInLightnessAndReadsBack)
{
    double previous = -1;
    for (int i = 0; i <= 100; ++i) {
        const render::Rgb c = render::field_colour(i / 100.0);
        const double luma = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        EXPECT_GT(luma, previous) << "t = " << i / 100.0 << ": perceptual maps get lighter monotonically";
        previous = luma;
        EXPECT_NEAR(render::field_position(c), i / 100.0, 1.0 / 128);
    }
}

TEST(FieldView, ALinearPotentialIsAGradientAcrossThePictureAndTheBarSpansItsRange)
{
    std::vector<double> phi;
    for (const Vec3& p : nested_cubes_mesh().vertices)
        phi.push_back(0.01 * p[0] - 0.02); // V: -20 mV at x = 0 to +20 mV at x = 4
    render::FieldSectionReport report;
    const Canvas picture =
        render::render_field_section(nested_cubes_mesh(), phi, {.width_px = 570, .height_px = 400, .axis = 2}, &report);
    EXPECT_EQ(report.field_min, -0.02);
    EXPECT_DOUBLE_EQ(report.field_max, 0.02);
    EXPECT_EQ(report.colour_min, report.field_min) << "unclipped: the bar shows the field's whole range";
    EXPECT_EQ(report.colour_max, report.field_max);
    EXPECT_GT(report.tets_cut, 10u);
    EXPECT_GT(report.outline_segments, 8u) << "the outer square and the inner cube's outline";
    // The plot is the left 400 px, the 4 mm fitted to 95%: 95 px/mm around x = 2 mm at px 200. P1 colours
    // follow x; 1/128 for the 8-bit colours and the nearest-colour lookup.
    const auto expected = [](double px) { return (2 + (px + 0.5 - 200) / 95) / 4; };
    for (const std::size_t px : {40, 120, 200, 280, 360})
        EXPECT_NEAR(column_mean(picture, px), expected(static_cast<double>(px)), 1.0 / 128) << px;
    EXPECT_LT(column_mean(picture, 40), column_mean(picture, 360));
    std::size_t black = 0;
    for (const render::Rgb& c : picture.pixels()) black += c == render::Rgb{0, 0, 0};
    EXPECT_GT(black, 400u) << "outlines and text";
}

TEST(FieldView, PerTetValuesAreFlatAndClippingNarrowsTheBar)
{
    std::vector<double> magnitude(nested_cubes_mesh().tets.size());
    for (std::size_t t = 0; t < magnitude.size(); ++t)
        magnitude[t] = nested_cubes_mesh().tet_labels[t] == 2 ? 5.0 : 1.0;
    magnitude[0] = 1000; // one spike
    render::FieldSectionReport full, clipped;
    render::render_field_section(nested_cubes_mesh(), magnitude, {.unit = "V/m"}, &full);
    EXPECT_EQ(full.colour_max, 1000);
    const Canvas picture =
        render::render_field_section(nested_cubes_mesh(), magnitude,
                                     {.width_px = 570, .height_px = 400, .unit = "V/m", .clip_percent = 1}, &clipped);
    EXPECT_EQ(clipped.field_max, 1000) << "the field's range is still reported";
    EXPECT_EQ(clipped.colour_max, 5);
    EXPECT_EQ(clipped.colour_min, 1);
    // The inner cube (tissue 2, 5 V/m) is the top colour, the outer one the bottom colour.
    EXPECT_NEAR(position_at(picture, 200, 200), 1.0, 0.01);
    EXPECT_NEAR(position_at(picture, 30, 200), 0.0, 0.01);
}

TEST(FieldView, WrongSizesAndSettingsAreRefused)
{
    using testing::expect_error;
    expect_error<InputError>(
        [] {
            render::render_field_section(nested_cubes_mesh(), {1.0, 2.0});
        },
        {"2 values for", "one per node or one per tet"});
    const std::vector<double> phi(nested_cubes_mesh().vertices.size(), 1.0);
    expect_error<InputError>([&] { render::render_field_section(nested_cubes_mesh(), phi, {.clip_percent = 60}); },
                             {"clip percent 60"});
    expect_error<InputError>(
        [&] { render::render_field_section(nested_cubes_mesh(), phi, {.at_centre = false, .position_mm = 9}); },
        {"misses the mesh"});
    const std::vector<double> nan(nested_cubes_mesh().vertices.size(), std::nan(""));
    expect_error<InputError>([&] { render::render_field_section(nested_cubes_mesh(), nan); },
                             {"no value of the field is finite"});
}

} // namespace
} // namespace tissuemesh

// Bar and line charts drawn on a canvas, with axes, ticks and labels in the built-in font.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "render/canvas.h"

namespace tissuemesh::render {

/// A pixel rectangle [x, x + width) x [y, y + height) of a canvas.
struct Panel {
    long x = 0, y = 0, width = 0, height = 0;
};

/// Bars of several series per bin: counts[b][s] of series s in bin b, drawn in stack_colours[s].
struct BarChart {
    std::string title, x_label;
    std::vector<std::string> bin_labels;     ///< #bins, under each bar (every other one when crowded)
    std::vector<std::vector<double>> counts; ///< #bins x #stacks
    std::vector<Rgb> stack_colours;          ///< #stacks
    /// true: the series side by side in each bin on a log10(1 + count) axis (every bar reads true against
    /// it); false, or more than 8 series: stacked, bottom first, on a linear axis.
    bool log_scale = true;
};

/// Draws `chart` in `panel`.
/// @throws InputError when counts, labels and colours disagree in size
void draw_bar_chart(Canvas& canvas, const Panel& panel, const BarChart& chart);

/// One polyline with a dot per point.
struct LineSeries {
    std::vector<std::array<double, 2>> points; ///< (x, y)
    Rgb colour{0, 0, 0};
};

struct LineChart {
    std::string title, x_label, y_label;
    std::vector<LineSeries> series;
    bool log_y = false; ///< y on a log10 axis (values <= 0 drawn on the bottom axis line, with a note)
};

/// Draws `chart` in `panel`, axes fitted to the data (x from a round number at or below its smallest value).
void draw_line_chart(Canvas& canvas, const Panel& panel, const LineChart& chart);

/// A short number for tick labels: "0.5", "12", "3.4k", "1.2M".
std::string short_number(double value);

} // namespace tissuemesh::render

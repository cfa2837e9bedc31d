#include "render/charts.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace tissuemesh::render {
namespace {

constexpr Rgb black{0, 0, 0}, grid{220, 220, 220};
constexpr long margin_left = 70, margin_right = 16, margin_top = 30, margin_bottom = 44;

/// A round step (1, 2 or 5 x 10^k) giving about `ticks` intervals over `range`.
double nice_step(double range, int ticks)
{
    const double raw = range / ticks, power = std::pow(10.0, std::floor(std::log10(raw)));
    for (const double m : {1.0, 2.0, 5.0})
        if (m * power >= raw) return m * power;
    return 10 * power;
}

Panel plot_area(const Panel& panel)
{
    return {panel.x + margin_left, panel.y + margin_top, panel.width - margin_left - margin_right,
            panel.height - margin_top - margin_bottom};
}

void draw_frame(Canvas& canvas, const Panel& panel, const Panel& area, const std::string& title,
                const std::string& x_label)
{
    canvas.draw_text(panel.x + margin_left, panel.y + 8, title, black);
    canvas.draw_text(area.x + (area.width - Canvas::text_width(x_label)) / 2, area.y + area.height + 26, x_label,
                     black);
    const double x0 = static_cast<double>(area.x), y1 = static_cast<double>(area.y + area.height);
    canvas.draw_line(x0, static_cast<double>(area.y), x0, y1, black);
    canvas.draw_line(x0, y1, static_cast<double>(area.x + area.width), y1, black);
}

/// A horizontal grid line with its label at height fraction f of the plot area.
void y_tick(Canvas& canvas, const Panel& area, double f, const std::string& label)
{
    const double y = static_cast<double>(area.y + area.height) - f * static_cast<double>(area.height);
    canvas.draw_line(static_cast<double>(area.x + 1), y, static_cast<double>(area.x + area.width), y, grid);
    canvas.draw_text(area.x - 6 - Canvas::text_width(label), std::lround(y) - 7, label, black);
}

} // namespace

std::string short_number(double value)
{
    char text[32];
    const double magnitude = std::abs(value);
    if (magnitude >= 1e6) std::snprintf(text, sizeof text, "%.3gM", value / 1e6);
    else if (magnitude >= 1e4) std::snprintf(text, sizeof text, "%.3gk", value / 1e3);
    else std::snprintf(text, sizeof text, "%.4g", value);
    return text;
}

void draw_bar_chart(Canvas& canvas, const Panel& panel, const BarChart& chart)
{
    if (chart.counts.size() != chart.bin_labels.size())
        throw InputError(concat("bar chart \"", chart.title, "\": ", chart.counts.size(), " bins but ",
                                chart.bin_labels.size(), " labels"));
    for (const auto& bin : chart.counts)
        if (bin.size() != chart.stack_colours.size())
            throw InputError(concat("bar chart \"", chart.title, "\": a bin has ", bin.size(), " stacks for ",
                                    chart.stack_colours.size(), " colours"));
    const Panel area = plot_area(panel);
    const std::size_t stacks = chart.stack_colours.size();
    // Side by side on a log axis, every bar reads true; a stack on a log axis would not (only its top would).
    const bool grouped = chart.log_scale && stacks <= 8;
    double max_value = 0;
    for (const auto& bin : chart.counts) {
        double total = 0;
        for (const double c : bin) total += c, max_value = std::max(max_value, grouped ? c : 0.0);
        if (!grouped) max_value = std::max(max_value, total);
    }
    auto height_of = [&](double value) {
        if (max_value <= 0) return 0.0;
        return grouped ? std::log10(1 + value) / std::log10(1 + max_value) : value / max_value;
    };
    if (grouped)
        for (double tick = 1; tick <= max_value; tick *= 10) y_tick(canvas, area, height_of(tick), short_number(tick));
    else if (max_value > 0)
        for (double step = nice_step(max_value, 4), tick = 0; tick <= max_value; tick += step)
            y_tick(canvas, area, height_of(tick), short_number(tick));
    const std::size_t bins = chart.counts.size();
    const double slot = static_cast<double>(area.width) / static_cast<double>(std::max<std::size_t>(bins, 1));
    const std::size_t label_every =
        static_cast<std::size_t>(std::ceil(static_cast<double>(Canvas::text_width("00000") + 8) / slot));
    const double bottom = static_cast<double>(area.y + area.height), h = static_cast<double>(area.height);
    for (std::size_t b = 0; b < bins; ++b) {
        const double left = static_cast<double>(area.x) + slot * static_cast<double>(b) + 0.1 * slot,
                     width = 0.8 * slot;
        double stacked = 0;
        for (std::size_t s = 0; s < stacks; ++s) {
            const double count = chart.counts[b][s];
            if (count <= 0) continue;
            if (grouped) {
                const double x0 = left + width * static_cast<double>(s) / static_cast<double>(stacks);
                canvas.fill_rect(std::lround(x0), std::lround(bottom - height_of(count) * h),
                                 std::max(std::lround(x0) + 1, std::lround(x0 + width / static_cast<double>(stacks))),
                                 std::lround(bottom), chart.stack_colours[s]);
            } else {
                const double top = stacked + height_of(count) * h;
                canvas.fill_rect(std::lround(left), std::lround(bottom - top), std::lround(left + width),
                                 std::lround(bottom - stacked), chart.stack_colours[s]);
                stacked = top;
            }
        }
        if (b % std::max<std::size_t>(label_every, 1) == 0)
            canvas.draw_text(area.x + std::lround(slot * static_cast<double>(b)), area.y + area.height + 6,
                             chart.bin_labels[b], black);
    }
    draw_frame(canvas, panel, area, chart.title, chart.x_label);
}

void draw_line_chart(Canvas& canvas, const Panel& panel, const LineChart& chart)
{
    const Panel area = plot_area(panel);
    double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min, y_min = x_min, y_max = -x_min;
    auto y_of = [&](double y) { return chart.log_y ? std::log10(y) : y; };
    for (const LineSeries& s : chart.series)
        for (const auto& [x, y] : s.points) {
            x_min = std::min(x_min, x), x_max = std::max(x_max, x);
            if (chart.log_y && !(y > 0)) continue;
            y_min = std::min(y_min, y_of(y)), y_max = std::max(y_max, y_of(y));
        }
    if (!(y_min <= y_max)) y_min = 0, y_max = 1;
    if (!chart.log_y) y_min = std::min(y_min, 0.0);
    if (chart.log_y) y_min = std::floor(y_min), y_max = std::ceil(y_max);
    if (y_max <= y_min) y_max = y_min + 1;
    if (!(x_min <= x_max)) x_min = 0, x_max = 1;
    // x from a round number at or below the smallest value (nodes start high after a tm-tetra mesh).
    const double x_step = nice_step(std::max(x_max - x_min, 1e-9 + 1e-6 * std::abs(x_max)), 4);
    x_min = std::floor(x_min / x_step) * x_step;
    if (x_max <= x_min) x_max = x_min + x_step;
    auto screen = [&](double x, double y) {
        return std::array<double, 2>{static_cast<double>(area.x) +
                                         static_cast<double>(area.width) * (x - x_min) / (x_max - x_min),
                                     static_cast<double>(area.y + area.height) -
                                         static_cast<double>(area.height) * (y_of(y) - y_min) / (y_max - y_min)};
    };
    if (chart.log_y)
        for (double e = y_min; e <= y_max; ++e)
            y_tick(canvas, area, (e - y_min) / (y_max - y_min), short_number(std::pow(10.0, e)));
    else
        for (double step = nice_step(y_max - y_min, 4), tick = std::ceil(y_min / step) * step; tick <= y_max;
             tick += step)
            y_tick(canvas, area, (tick - y_min) / (y_max - y_min), short_number(tick));
    for (double tick = x_min; tick <= x_max + 1e-9 * std::abs(x_max) + 1e-12; tick += x_step) {
        const double x = screen(tick, chart.log_y ? std::pow(10.0, y_min) : y_min)[0];
        canvas.draw_line(x, static_cast<double>(area.y + area.height), x, static_cast<double>(area.y + area.height + 4),
                         black);
        const std::string label = short_number(tick);
        canvas.draw_text(std::lround(x) - Canvas::text_width(label) / 2, area.y + area.height + 8, label, black);
    }
    bool zeros_on_axis = false;
    for (const LineSeries& s : chart.series) {
        std::vector<std::array<double, 2>> points;
        for (const auto& [x, y] : s.points) {
            // A log axis has no 0: such points sit on the bottom axis line, and a note says so.
            const bool on_axis = chart.log_y && !(y > 0);
            zeros_on_axis = zeros_on_axis || on_axis;
            points.push_back(screen(x, on_axis ? std::pow(10.0, y_min) : y));
        }
        for (std::size_t i = 0; i + 1 < points.size(); ++i)
            canvas.draw_line(points[i][0], points[i][1], points[i + 1][0], points[i + 1][1], s.colour, 2);
        for (const auto& p : points)
            canvas.fill_rect(std::lround(p[0]) - 3, std::lround(p[1]) - 3, std::lround(p[0]) + 3, std::lround(p[1]) + 3,
                             s.colour);
    }
    draw_frame(canvas, panel, area, chart.title, chart.x_label);
    if (zeros_on_axis)
        canvas.draw_text(area.x + area.width - Canvas::text_width("values <= 0 drawn on the axis"), panel.y + 8,
                         "values <= 0 drawn on the axis", {90, 90, 90});
    if (!chart.y_label.empty()) canvas.draw_text(area.x + 8, area.y + 4, chart.y_label, {90, 90, 90});
}

} // namespace tissuemesh::render

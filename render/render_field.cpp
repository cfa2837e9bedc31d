#include "render/render_field.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "render/detail/section_frame.h"

namespace tissuemesh::render {
namespace {

using detail::Point2;

constexpr long bar_panel_px = 170;
const Rgb missing_colour{160, 160, 160};

/// The colour range: the finite values' extremes, or with clipping the values at clip_percent from each end.
std::array<double, 2> colour_range(const std::vector<double>& values, double clip_percent, std::array<double, 2>& full)
{
    std::vector<double> finite;
    finite.reserve(values.size());
    for (const double value : values)
        if (std::isfinite(value)) finite.push_back(value);
    if (finite.empty()) throw InputError("field view: no value of the field is finite; nothing to draw");
    std::sort(finite.begin(), finite.end());
    full = {finite.front(), finite.back()};
    const double last = static_cast<double>(finite.size() - 1);
    const auto at = [&](double q) { return finite[static_cast<std::size_t>(std::llround(q * last))]; };
    return {at(clip_percent / 100), at(1 - clip_percent / 100)};
}

/// A tick label with 3 significant digits ("0.159", "-74.6", "1.2e-06"): the built-in font has capitals
/// only, so a unit prefix would read wrong ("MV" for mV); values stay in the SI unit.
std::string tick_text(double value)
{
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%.3g", value);
    return buffer;
}

/// Fills the screen triangle (a, b, c) with the colours of the values linear between its corners.
void fill_gradient(Canvas& canvas, const std::array<Point2, 3>& p, const std::array<double, 3>& value, double low,
                   double span)
{
    const double area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    if (area == 0 || !std::isfinite(area)) return;
    const long x0 = std::max(0L, static_cast<long>(std::floor(std::min({p[0][0], p[1][0], p[2][0]}))));
    const long x1 = std::min(static_cast<long>(canvas.width()) - 1,
                             static_cast<long>(std::ceil(std::max({p[0][0], p[1][0], p[2][0]}))));
    const long y0 = std::max(0L, static_cast<long>(std::floor(std::min({p[0][1], p[1][1], p[2][1]}))));
    const long y1 = std::min(static_cast<long>(canvas.height()) - 1,
                             static_cast<long>(std::ceil(std::max({p[0][1], p[1][1], p[2][1]}))));
    const bool finite = is_finite(value);
    for (long y = y0; y <= y1; ++y)
        for (long x = x0; x <= x1; ++x) {
            const double px = static_cast<double>(x) + 0.5, py = static_cast<double>(y) + 0.5;
            const double wa = ((p[1][0] - px) * (p[2][1] - py) - (p[1][1] - py) * (p[2][0] - px)) / area;
            const double wb = ((p[2][0] - px) * (p[0][1] - py) - (p[2][1] - py) * (p[0][0] - px)) / area;
            const double wc = 1 - wa - wb;
            if (wa < 0 || wb < 0 || wc < 0) continue;
            const double v = wa * value[0] + wb * value[1] + wc * value[2];
            canvas.set(x, y, finite ? field_colour((v - low) / span) : missing_colour);
        }
}

void draw_colour_bar(Canvas& canvas, const FieldSectionOptions& options, const FieldSectionReport& report)
{
    const long width = static_cast<long>(canvas.width()), height = static_cast<long>(canvas.height());
    const long x = width - bar_panel_px + 16, top = 84, bottom = std::max(top + 40, height - 110), bar = 28;
    canvas.draw_text(x - 6, 24, options.quantity, {0, 0, 0});
    if (!options.unit.empty()) canvas.draw_text(x - 6, 46, concat("(", options.unit, ")"), {0, 0, 0});
    for (long y = top; y <= bottom; ++y)
        canvas.fill_rect(x, y, x + bar, y + 1,
                         field_colour(static_cast<double>(bottom - y) / static_cast<double>(bottom - top)));
    const Rgb ink{0, 0, 0};
    const double left = static_cast<double>(x), right = static_cast<double>(x + bar), up = static_cast<double>(top),
                 down = static_cast<double>(bottom);
    canvas.draw_line(left, up, right, up, ink), canvas.draw_line(left, down, right, down, ink);
    canvas.draw_line(left, up, left, down, ink), canvas.draw_line(right, up, right, down, ink);
    for (int i = 0; i <= 4; ++i) {
        const double t = i / 4.0, value = report.colour_min + t * (report.colour_max - report.colour_min);
        const double y = static_cast<double>(bottom) - t * static_cast<double>(bottom - top);
        canvas.draw_line(static_cast<double>(x + bar), y, static_cast<double>(x + bar + 6), y, ink);
        canvas.draw_text(x + bar + 10, std::lround(y) - 7, tick_text(value), ink);
    }
    if (options.clip_percent > 0)
        canvas.draw_text(x - 6, bottom + 20, concat("clipped ", format_mm(options.clip_percent, 1), "%"), ink);
}

} // namespace

Rgb field_colour(double t)
{
    // The deciles of viridis (matplotlib's default map), joined linearly.
    static const std::array<Rgb, 11> anchors{{{68, 1, 84},
                                              {72, 36, 117},
                                              {65, 68, 135},
                                              {53, 95, 141},
                                              {42, 120, 142},
                                              {33, 145, 140},
                                              {34, 168, 132},
                                              {68, 191, 112},
                                              {122, 209, 81},
                                              {189, 223, 38},
                                              {253, 231, 37}}};
    const double s = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 10;
    const auto i = std::min<std::size_t>(9, static_cast<std::size_t>(s));
    return mix(anchors[i], anchors[i + 1], s - static_cast<double>(i));
}

double field_position(const Rgb& colour)
{
    double best = 0, best_distance = 1e30;
    for (int i = 0; i <= 1024; ++i) {
        const Rgb c = field_colour(i / 1024.0);
        double d = 0;
        for (std::size_t k = 0; k < 3; ++k) d += (c[k] - colour[k]) * (c[k] - colour[k]);
        if (d < best_distance) best_distance = d, best = i / 1024.0;
    }
    return best;
}

Canvas render_field_section(const TetMesh& mesh, const std::vector<double>& values, const FieldSectionOptions& options,
                            FieldSectionReport* report)
{
    const bool nodal = values.size() == mesh.vertices.size();
    if (!nodal && values.size() != mesh.tets.size())
        throw InputError(concat("field view: ", values.size(), " values for ", mesh.vertices.size(), " nodes and ",
                                mesh.tets.size(), " tets; give one per node or one per tet"));
    if (!(options.clip_percent >= 0 && options.clip_percent < 50))
        throw InputError(concat("field view: clip percent ", options.clip_percent, " is not in [0, 50)"));
    Canvas canvas(options.width_px, options.height_px, {255, 255, 255});
    const double plot_width = std::max(1.0, static_cast<double>(options.width_px) - bar_panel_px);
    const detail::SectionFrame frame =
        detail::fit_section(mesh, options.axis, options.at_centre, options.position_mm, plot_width,
                            static_cast<double>(options.height_px), "field view");
    FieldSectionReport counts;
    counts.position_mm = frame.at;
    std::array<double, 2> full{};
    const std::array<double, 2> range = colour_range(values, options.clip_percent, full);
    counts.field_min = full[0], counts.field_max = full[1], counts.colour_min = range[0], counts.colour_max = range[1];
    const double span = range[1] > range[0] ? range[1] - range[0] : 1.0;
    std::vector<Point2> polygon;
    std::vector<double> at_points;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        detail::cut_tet(mesh, t, frame, polygon, nodal ? &values : nullptr, &at_points);
        if (polygon.empty()) continue;
        ++counts.tets_cut;
        for (Point2& p : polygon) p = frame.to_screen(p);
        if (!nodal) {
            canvas.fill_polygon(polygon, std::isfinite(values[t]) ? field_colour((values[t] - range[0]) / span)
                                                                  : missing_colour);
            continue;
        }
        for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
            fill_gradient(canvas, {polygon[0], polygon[k], polygon[k + 1]},
                          {at_points[0], at_points[k], at_points[k + 1]}, range[0], span);
    }
    if (options.outlines) {
        const auto segments = detail::tissue_outlines(mesh, frame);
        counts.outline_segments = segments.size();
        for (const auto& [a, b] : segments) {
            const Point2 p = frame.to_screen(a), q = frame.to_screen(b);
            canvas.draw_line(p[0], p[1], q[0], q[1], {0, 0, 0}, 1.5);
        }
    }
    draw_colour_bar(canvas, options, counts);
    const std::string caption = concat("xyz"[options.axis], " = ", format_mm(frame.at, 1), " mm",
                                       options.title.empty() ? "" : "  ", options.title);
    canvas.draw_text(8, static_cast<long>(options.height_px) - 22, caption, {0, 0, 0});
    if (report) *report = counts;
    return canvas;
}

} // namespace tissuemesh::render

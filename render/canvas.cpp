#include "render/canvas.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "render/detail/font5x7.h"

namespace tissuemesh::render {

Rgb mix(const Rgb& a, const Rgb& b, double t)
{
    Rgb out{};
    for (int c = 0; c < 3; ++c) out[c] = static_cast<std::uint8_t>(std::lround((1 - t) * a[c] + t * b[c]));
    return out;
}

Canvas::Canvas(std::size_t width, std::size_t height, const Rgb& fill) : width_(width), height_(height)
{
    if (width == 0 || height == 0 || width > 16384 || height > 16384)
        throw InputError(concat("picture size ", width, " x ", height, " px is out of range; use 1..16384 px a side"));
    pixels_.assign(width * height, fill);
    depth_.assign(width * height, std::numeric_limits<double>::infinity());
}

void Canvas::set(long x, long y, const Rgb& colour)
{
    if (x < 0 || y < 0 || x >= static_cast<long>(width_) || y >= static_cast<long>(height_)) return;
    pixels_[static_cast<std::size_t>(y) * width_ + static_cast<std::size_t>(x)] = colour;
}

void Canvas::blend(long x, long y, const Rgb& colour, double opacity)
{
    if (x < 0 || y < 0 || x >= static_cast<long>(width_) || y >= static_cast<long>(height_)) return;
    Rgb& pixel = pixels_[static_cast<std::size_t>(y) * width_ + static_cast<std::size_t>(x)];
    pixel = mix(pixel, colour, opacity);
}

void Canvas::fill_rect(long x0, long y0, long x1, long y1, const Rgb& colour)
{
    for (long y = std::max(0L, y0); y < std::min(static_cast<long>(height_), y1); ++y)
        for (long x = std::max(0L, x0); x < std::min(static_cast<long>(width_), x1); ++x) set(x, y, colour);
}

void Canvas::draw_line(double x0, double y0, double x1, double y1, const Rgb& colour, double thickness_px)
{
    // Stamps a square of the thickness at steps of half a pixel along the segment.
    const double length = std::hypot(x1 - x0, y1 - y0);
    const int steps = std::max(1, static_cast<int>(std::ceil(2 * length)));
    const double half = thickness_px / 2;
    for (int s = 0; s <= steps; ++s) {
        const double t = static_cast<double>(s) / steps, x = x0 + t * (x1 - x0), y = y0 + t * (y1 - y0);
        for (long py = std::lround(y - half); py < std::lround(y + half) || py == std::lround(y - half); ++py)
            for (long px = std::lround(x - half); px < std::lround(x + half) || px == std::lround(x - half); ++px)
                set(px, py, colour);
    }
}

std::size_t Canvas::draw_triangle(const std::array<double, 3>& a, const std::array<double, 3>& b,
                                  const std::array<double, 3>& c, const Rgb& colour)
{
    const double area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if (area == 0 || !std::isfinite(area)) return 0;
    const long x_lo = std::max(0L, static_cast<long>(std::floor(std::min({a[0], b[0], c[0]}))));
    const long x_hi =
        std::min(static_cast<long>(width_) - 1, static_cast<long>(std::ceil(std::max({a[0], b[0], c[0]}))));
    const long y_lo = std::max(0L, static_cast<long>(std::floor(std::min({a[1], b[1], c[1]}))));
    const long y_hi =
        std::min(static_cast<long>(height_) - 1, static_cast<long>(std::ceil(std::max({a[1], b[1], c[1]}))));
    std::size_t written = 0;
    for (long y = y_lo; y <= y_hi; ++y)
        for (long x = x_lo; x <= x_hi; ++x) {
            const double px = static_cast<double>(x) + 0.5, py = static_cast<double>(y) + 0.5;
            // Barycentric weights by edge functions; a pixel centre on an edge belongs to both sides.
            const double wa = ((b[0] - px) * (c[1] - py) - (b[1] - py) * (c[0] - px)) / area;
            const double wb = ((c[0] - px) * (a[1] - py) - (c[1] - py) * (a[0] - px)) / area;
            const double wc = 1 - wa - wb;
            if (wa < 0 || wb < 0 || wc < 0) continue;
            const double depth = wa * a[2] + wb * b[2] + wc * c[2];
            const std::size_t i = static_cast<std::size_t>(y) * width_ + static_cast<std::size_t>(x);
            if (depth >= depth_[i]) continue;
            depth_[i] = depth;
            pixels_[i] = colour;
            ++written;
        }
    return written;
}

void Canvas::fill_polygon(const std::vector<std::array<double, 2>>& points, const Rgb& colour, double opacity)
{
    if (points.size() < 3) return;
    double y_min = points[0][1], y_max = points[0][1];
    for (const auto& p : points) y_min = std::min(y_min, p[1]), y_max = std::max(y_max, p[1]);
    // Scan lines through pixel centres; each crosses a convex polygon's edges at most twice.
    for (long y = std::max(0L, static_cast<long>(std::floor(y_min)));
         y <= std::min(static_cast<long>(height_) - 1, static_cast<long>(y_max)); ++y) {
        const double py = static_cast<double>(y) + 0.5;
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (std::size_t e = 0; e < points.size(); ++e) {
            const auto& p = points[e];
            const auto& q = points[(e + 1) % points.size()];
            if ((p[1] <= py) == (q[1] <= py)) continue;
            const double x = p[0] + (py - p[1]) / (q[1] - p[1]) * (q[0] - p[0]);
            lo = std::min(lo, x), hi = std::max(hi, x);
        }
        if (!(lo <= hi)) continue;
        for (long x = static_cast<long>(std::ceil(lo - 0.5)); static_cast<double>(x) + 0.5 <= hi; ++x)
            blend(x, y, colour, opacity);
    }
}

long Canvas::draw_text(long x, long y, const std::string& text, const Rgb& colour, int scale)
{
    long cursor = x;
    for (const char c : text) {
        const auto& rows = detail::glyph(c);
        for (int row = 0; row < 7; ++row)
            for (int column = 0; column < 5; ++column)
                if (rows[static_cast<std::size_t>(row)] & (0x10 >> column))
                    fill_rect(cursor + column * scale, y + row * scale, cursor + (column + 1) * scale,
                              y + (row + 1) * scale, colour);
        cursor += 6 * scale;
    }
    return cursor - x;
}

long Canvas::text_width(const std::string& text, int scale)
{
    return text.empty() ? 0 : static_cast<long>(text.size()) * 6 * scale - scale;
}

} // namespace tissuemesh::render

// Canvas: an RGB picture with a depth buffer, and the few primitives our pictures need.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace tissuemesh::render {

using Rgb = std::array<std::uint8_t, 3>;

/// `a` blended towards `b`: (1 - t) a + t b, t in [0, 1].
Rgb mix(const Rgb& a, const Rgb& b, double t);

/// A width x height RGB picture, row 0 at the top, with a depth per pixel (smaller = nearer) for
/// draw_triangle(). Pixel (x, y) is the unit square [x, x+1) x [y, y+1); its centre is sampled.
class Canvas {
public:
    /// @throws InputError when a side is 0 or larger than 16384 px
    Canvas(std::size_t width, std::size_t height, const Rgb& fill = {255, 255, 255});

    std::size_t width() const { return width_; }
    std::size_t height() const { return height_; }
    const Rgb& at(std::size_t x, std::size_t y) const { return pixels_[y * width_ + x]; }
    const std::vector<Rgb>& pixels() const { return pixels_; }

    /// Sets pixel (x, y) when it lies on the canvas (no depth test).
    void set(long x, long y, const Rgb& colour);
    /// Blends pixel (x, y) towards `colour` by `opacity` (0: unchanged, 1: replaced).
    void blend(long x, long y, const Rgb& colour, double opacity);
    void fill_rect(long x0, long y0, long x1, long y1, const Rgb& colour); ///< [x0, x1) x [y0, y1)
    /// A line between pixel positions (continuous coordinates), `thickness_px` wide, no depth test.
    void draw_line(double x0, double y0, double x1, double y1, const Rgb& colour, double thickness_px = 1);
    /// Fills the triangle of screen points (x, y, depth) where it is nearer than what the pixel holds;
    /// depth is interpolated linearly. `colour_at(depth)` is not needed: the caller shades per triangle.
    /// Returns the number of pixels written.
    std::size_t draw_triangle(const std::array<double, 3>& a, const std::array<double, 3>& b,
                              const std::array<double, 3>& c, const Rgb& colour);
    /// Fills a convex polygon of screen points (x, y), blending by `opacity`, no depth test.
    void fill_polygon(const std::vector<std::array<double, 2>>& points, const Rgb& colour, double opacity = 1);
    /// Text in the built-in 5 x 7 bitmap font (printable ASCII; lower case drawn as capitals), top-left at
    /// (x, y), each font pixel `scale` px wide. Returns the width in px.
    long draw_text(long x, long y, const std::string& text, const Rgb& colour, int scale = 2);
    /// Width in px of `text` at `scale` (6 font pixels a character, no trailing gap).
    static long text_width(const std::string& text, int scale = 2);

private:
    std::size_t width_, height_;
    std::vector<Rgb> pixels_;
    std::vector<double> depth_;
};

} // namespace tissuemesh::render

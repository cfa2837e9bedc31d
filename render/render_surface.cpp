#include "render/render_surface.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "core/error.h"
#include "render/tissue_colours.h"

namespace tissuemesh::render {
namespace {

/// Camera frame: `toward` points from the model to the camera, `right` and `up` span the screen.
struct Camera {
    Vec3 toward, right, up;
};

Camera make_camera(double azimuth_deg, double elevation_deg)
{
    const double az = azimuth_deg * std::numbers::pi / 180, el = elevation_deg * std::numbers::pi / 180;
    const Vec3 toward{std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
    Vec3 right = cross(Vec3{0, 0, 1}, toward);
    if (norm(right) < 1e-9) right = {0, 1, 0}; // looking straight down or up
    right = (1 / norm(right)) * right;
    return {toward, right, cross(toward, right)};
}

bool in_cut(const Vec3& p, CutAway cut, const Vec3& at)
{
    switch (cut) {
    case CutAway::none: return false;
    case CutAway::half: return p[0] > at[0];
    case CutAway::wedge: return p[0] > at[0] && p[1] > at[1];
    }
    return false;
}

} // namespace

CutAway parse_cut_away(const std::string& name)
{
    if (name == "none") return CutAway::none;
    if (name == "half") return CutAway::half;
    if (name == "wedge") return CutAway::wedge;
    throw InputError(concat("unknown cut-away \"", name, "\"; use none, half or wedge"));
}

Canvas render_surface(const InterfaceComplex& complex, const SurfaceViewOptions& options, SurfaceViewReport* report)
{
    if (complex.triangles.empty())
        throw InputError("surface view: the interface complex has no triangle; nothing to draw");
    Vec3 low = complex.vertices[complex.triangles[0][0]], high = low;
    std::set<Label> tissues;
    for (std::size_t t = 0; t < complex.triangles.size(); ++t) {
        for (const std::uint32_t v : complex.triangles[t])
            for (int a = 0; a < 3; ++a)
                low[a] = std::min(low[a], complex.vertices[v][a]), high[a] = std::max(high[a], complex.vertices[v][a]);
        for (const Label label : {complex.sides[t].from, complex.sides[t].to})
            if (label != complex.background) tissues.insert(label);
    }
    const Vec3 centre = 0.5 * (low + high);
    const Vec3 cut_at = options.cut_at_centre ? centre : options.cut_point_mm;
    const Camera camera = make_camera(options.azimuth_deg, options.elevation_deg);
    // The bounding sphere fits the picture with a 5% margin whatever the view direction.
    const double radius = std::max(0.5 * norm(high - low), 1e-9);
    const double side = static_cast<double>(std::min(options.width_px, options.height_px));
    const double scale = 0.95 * side / (2 * radius);
    const double cx = 0.5 * static_cast<double>(options.width_px), cy = 0.5 * static_cast<double>(options.height_px);

    Canvas canvas(options.width_px, options.height_px, {255, 255, 255});
    SurfaceViewReport counts;
    for (std::size_t t = 0; t < complex.triangles.size(); ++t) {
        const Triangle& tri = complex.triangles[t];
        const Vec3 &a = complex.vertices[tri[0]], &b = complex.vertices[tri[1]], &c = complex.vertices[tri[2]];
        if (in_cut((1.0 / 3) * (a + b + c), options.cut, cut_at)) {
            ++counts.triangles_cut;
            continue;
        }
        ++counts.triangles_drawn;
        const Vec3 normal = cross(b - a, c - a);
        const double length = norm(normal);
        if (length == 0) continue;
        const double facing = dot(normal, camera.toward) / length; // > 0: the camera is on the `to` side
        const Label near_side = facing > 0 ? complex.sides[t].to : complex.sides[t].from;
        const Label far_side = facing > 0 ? complex.sides[t].from : complex.sides[t].to;
        Rgb colour;
        if (near_side != complex.background) colour = tissue_colour(near_side);
        else colour = mix({0, 0, 0}, tissue_colour(far_side), 0.35 + 0.65 * std::abs(facing));
        auto screen = [&](const Vec3& p) {
            const Vec3 d = p - centre;
            return std::array<double, 3>{cx + scale * dot(d, camera.right), cy - scale * dot(d, camera.up),
                                         -dot(d, camera.toward)};
        };
        canvas.draw_triangle(screen(a), screen(b), screen(c), colour);
    }
    for (const Rgb& pixel : canvas.pixels()) counts.pixels_covered += pixel != Rgb{255, 255, 255};
    if (options.legend) draw_legend(canvas, 8, 8, tissue_legend({tissues.begin(), tissues.end()}, complex.names));
    if (!options.title.empty())
        canvas.draw_text(8, static_cast<long>(options.height_px) - 22, options.title, {0, 0, 0});
    if (report) *report = counts;
    return canvas;
}

} // namespace tissuemesh::render

#include "render/render_section.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "core/error.h"
#include "render/tissue_colours.h"

namespace tissuemesh::render {
namespace {

using Point2 = std::array<double, 2>;

/// The polygon where the plane axis = at cuts tet `t` (3 or 4 points, convex, in order), in the plane's
/// (u, v) coordinates; empty when it does not cross. A vertex on the plane counts as above it, so a
/// tet touching the plane only there is not cut.
std::vector<Point2> cut_polygon(const TetMesh& mesh, std::size_t t, int axis, int u, int v, double at)
{
    std::array<double, 4> d{};
    int above = 0;
    for (int i = 0; i < 4; ++i) {
        d[i] = mesh.vertices[mesh.tets[t][i]][axis] - at;
        above += d[i] >= 0;
    }
    if (above == 0 || above == 4) return {};
    std::vector<Point2> points;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
            if ((d[i] >= 0) == (d[j] >= 0)) continue;
            const Vec3 &p = mesh.vertices[mesh.tets[t][i]], &q = mesh.vertices[mesh.tets[t][j]];
            const double s = d[i] / (d[i] - d[j]);
            points.push_back({p[u] + s * (q[u] - p[u]), p[v] + s * (q[v] - p[v])});
        }
    Point2 mid{0, 0};
    for (const Point2& p : points) mid[0] += p[0] / static_cast<double>(points.size()), mid[1] += p[1] / static_cast<double>(points.size());
    std::sort(points.begin(), points.end(), [&](const Point2& a, const Point2& b) {
        return std::atan2(a[1] - mid[1], a[0] - mid[0]) < std::atan2(b[1] - mid[1], b[0] - mid[0]);
    });
    return points;
}

} // namespace

Canvas render_section(const TetMesh& mesh, const LabelImage* image, const std::vector<double>* error_volume_mm3,
                      const SectionViewOptions& options, SectionViewReport* report)
{
    if (mesh.tets.empty()) throw InputError("section view: the mesh has no tetrahedron; nothing to draw");
    if (options.axis < 0 || options.axis > 2) throw InputError(concat("section view: axis ", options.axis, " is not 0 (x), 1 (y) or 2 (z)"));
    if (error_volume_mm3 && error_volume_mm3->size() != mesh.tets.size())
        throw InputError(concat("section view: ", error_volume_mm3->size(), " error volumes for ", mesh.tets.size(), " tets"));
    const int axis = options.axis, u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
    Vec3 low = mesh.vertices[0], high = low;
    for (const Vec3& p : mesh.vertices)
        for (int a = 0; a < 3; ++a) low[a] = std::min(low[a], p[a]), high[a] = std::max(high[a], p[a]);
    const double at = options.at_centre ? 0.5 * (low[axis] + high[axis]) : options.position_mm;
    if (at < low[axis] || at > high[axis])
        throw InputError(concat("section view: the plane ", "xyz"[axis], " = ", format_mm(at), " mm misses the mesh (", format_mm(low[axis]),
                                " .. ", format_mm(high[axis]), " mm)"));

    const double w = static_cast<double>(options.width_px), h = static_cast<double>(options.height_px);
    const double scale = 0.95 * std::min(w / std::max(high[u] - low[u], 1e-9), h / std::max(high[v] - low[v], 1e-9));
    const double mid_u = 0.5 * (low[u] + high[u]), mid_v = 0.5 * (low[v] + high[v]);
    auto to_screen = [&](const Point2& p) { return Point2{0.5 * w + scale * (p[0] - mid_u), 0.5 * h - scale * (p[1] - mid_v)}; };

    Canvas canvas(options.width_px, options.height_px, {255, 255, 255});
    std::set<Label> shown;
    if (image) {
        for (std::size_t y = 0; y < options.height_px; ++y)
            for (std::size_t x = 0; x < options.width_px; ++x) {
                Vec3 world{};
                world[axis] = at;
                world[u] = mid_u + (static_cast<double>(x) + 0.5 - 0.5 * w) / scale;
                world[v] = mid_v - (static_cast<double>(y) + 0.5 - 0.5 * h) / scale;
                const Vec3 index = image->world_to_index(world);
                const Index3 voxel{std::llround(index[0]), std::llround(index[1]), std::llround(index[2])};
                if (!image->contains(voxel)) continue;
                const Label label = image->at(voxel[0], voxel[1], voxel[2]);
                canvas.set(static_cast<long>(x), static_cast<long>(y), label == 0 ? Rgb{225, 225, 225} : mix({255, 255, 255}, tissue_colour(label), 0.35));
            }
    }
    const double error_threshold = options.min_error_voxels * (image ? image->voxel_volume_mm3() : 1.0);
    SectionViewReport counts{at, 0, 0};
    std::vector<std::vector<Point2>> outlines;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        std::vector<Point2> polygon = cut_polygon(mesh, t, axis, u, v, at);
        if (polygon.empty()) continue;
        ++counts.tets_cut;
        for (Point2& p : polygon) p = to_screen(p);
        shown.insert(mesh.tet_labels[t]);
        const bool high_error = error_volume_mm3 && (*error_volume_mm3)[t] >= error_threshold && (*error_volume_mm3)[t] > 0;
        counts.tets_highlighted += high_error;
        canvas.fill_polygon(polygon, high_error ? error_colour : tissue_colour(mesh.tet_labels[t]), high_error ? 0.85 : options.tet_opacity);
        outlines.push_back(std::move(polygon));
    }
    const Rgb edge_colour{70, 70, 70};
    for (const auto& polygon : outlines)
        for (std::size_t e = 0; e < polygon.size(); ++e) {
            const Point2 &p = polygon[e], &q = polygon[(e + 1) % polygon.size()];
            canvas.draw_line(p[0], p[1], q[0], q[1], edge_colour, 1);
        }
    if (options.legend) {
        std::vector<LegendEntry> entries = tissue_legend({shown.begin(), shown.end()}, mesh.names);
        if (counts.tets_highlighted > 0)
            entries.push_back({error_colour, concat("error >= ", format_mm(options.min_error_voxels, 2), " voxel")});
        draw_legend(canvas, 8, 8, entries);
    }
    const std::string caption = concat("xyz"[axis], " = ", format_mm(at, 1), " mm", options.title.empty() ? "" : "  ", options.title);
    canvas.draw_text(8, static_cast<long>(options.height_px) - 22, caption, {0, 0, 0});
    if (report) *report = counts;
    return canvas;
}

} // namespace tissuemesh::render

#include "render/detail/section_frame.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/error.h"

namespace tissuemesh::render::detail {

Vec3 SectionFrame::to_world(double x, double y) const
{
    Vec3 world{};
    world[static_cast<std::size_t>(axis)] = at;
    world[static_cast<std::size_t>(u)] = mid_u + (x - centre_x) / scale;
    world[static_cast<std::size_t>(v)] = mid_v - (y - centre_y) / scale;
    return world;
}

SectionFrame fit_section(const TetMesh& mesh, int axis, bool at_centre, double position_mm, double plot_width,
                         double height, const std::string& view)
{
    if (mesh.tets.empty() || mesh.vertices.empty())
        throw InputError(concat(view, ": the mesh has no tetrahedron; nothing to draw"));
    if (axis < 0 || axis > 2) throw InputError(concat(view, ": axis ", axis, " is not 0 (x), 1 (y) or 2 (z)"));
    SectionFrame frame;
    frame.axis = axis, frame.u = axis == 0 ? 1 : 0, frame.v = axis == 2 ? 1 : 2;
    Vec3 low = mesh.vertices[0], high = low;
    for (const Vec3& p : mesh.vertices)
        for (std::size_t a = 0; a < 3; ++a) low[a] = std::min(low[a], p[a]), high[a] = std::max(high[a], p[a]);
    const auto a = static_cast<std::size_t>(axis), u = static_cast<std::size_t>(frame.u),
               v = static_cast<std::size_t>(frame.v);
    frame.at = at_centre ? 0.5 * (low[a] + high[a]) : position_mm;
    if (!(frame.at >= low[a] && frame.at <= high[a]))
        throw InputError(concat(view, ": the plane ", "xyz"[axis], " = ", format_mm(frame.at), " mm misses the mesh (",
                                format_mm(low[a]), " .. ", format_mm(high[a]), " mm)"));
    frame.scale =
        0.95 * std::min(plot_width / std::max(high[u] - low[u], 1e-9), height / std::max(high[v] - low[v], 1e-9));
    frame.mid_u = 0.5 * (low[u] + high[u]), frame.mid_v = 0.5 * (low[v] + high[v]);
    frame.centre_x = 0.5 * plot_width, frame.centre_y = 0.5 * height;
    return frame;
}

void cut_tet(const TetMesh& mesh, std::size_t t, const SectionFrame& frame, std::vector<Point2>& points,
             const std::vector<double>* node_values, std::vector<double>* values)
{
    points.clear();
    if (values) values->clear();
    const auto axis = static_cast<std::size_t>(frame.axis), u = static_cast<std::size_t>(frame.u),
               v = static_cast<std::size_t>(frame.v);
    std::array<double, 4> d{};
    int above = 0;
    for (std::size_t i = 0; i < 4; ++i) {
        d[i] = mesh.vertices[mesh.tets[t][i]][axis] - frame.at;
        above += d[i] >= 0;
    }
    if (above == 0 || above == 4) return;
    std::vector<double> crossing_values;
    for (std::size_t i = 0; i < 4; ++i)
        for (std::size_t j = i + 1; j < 4; ++j) {
            if ((d[i] >= 0) == (d[j] >= 0)) continue;
            const Vec3 &p = mesh.vertices[mesh.tets[t][i]], &q = mesh.vertices[mesh.tets[t][j]];
            const double s = d[i] / (d[i] - d[j]);
            points.push_back({p[u] + s * (q[u] - p[u]), p[v] + s * (q[v] - p[v])});
            if (node_values)
                crossing_values.push_back((1 - s) * (*node_values)[mesh.tets[t][i]] +
                                          s * (*node_values)[mesh.tets[t][j]]);
        }
    // Around the centre, so that the polygon is convex and in order.
    Point2 mid{0, 0};
    for (const Point2& p : points)
        mid[0] += p[0] / static_cast<double>(points.size()), mid[1] += p[1] / static_cast<double>(points.size());
    std::vector<std::size_t> order(points.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return std::atan2(points[a][1] - mid[1], points[a][0] - mid[0]) <
               std::atan2(points[b][1] - mid[1], points[b][0] - mid[0]);
    });
    std::vector<Point2> sorted;
    for (const std::size_t i : order) {
        sorted.push_back(points[i]);
        if (values && node_values) values->push_back(crossing_values[i]);
    }
    points = std::move(sorted);
}

std::vector<std::array<Point2, 2>> tissue_outlines(const TetMesh& mesh, const SectionFrame& frame)
{
    // Faces of the cut tets, each as (sorted vertices, label): a face crossing the plane has both its tets cut.
    struct Face {
        std::array<std::uint32_t, 3> v;
        Label label;
    };
    std::vector<Face> faces;
    const auto axis = static_cast<std::size_t>(frame.axis);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        int above = 0;
        for (const std::uint32_t i : mesh.tets[t]) above += mesh.vertices[i][axis] - frame.at >= 0;
        if (above == 0 || above == 4) continue;
        for (std::size_t skip = 0; skip < 4; ++skip) {
            std::array<std::uint32_t, 3> f{};
            for (std::size_t i = 0, n = 0; i < 4; ++i)
                if (i != skip) f[n++] = mesh.tets[t][i];
            std::sort(f.begin(), f.end());
            faces.push_back({f, mesh.tet_labels[t]});
        }
    }
    std::sort(faces.begin(), faces.end(),
              [](const Face& a, const Face& b) { return a.v < b.v || (a.v == b.v && a.label < b.label); });
    std::vector<std::array<Point2, 2>> segments;
    const auto u = static_cast<std::size_t>(frame.u), v = static_cast<std::size_t>(frame.v);
    for (std::size_t i = 0; i < faces.size();) {
        std::size_t j = i + 1;
        while (j < faces.size() && faces[j].v == faces[i].v) ++j;
        const bool outline = j - i == 1 || faces[i].label != faces[j - 1].label;
        if (outline) {
            std::vector<Point2> ends;
            for (std::size_t a = 0; a < 3; ++a) {
                const Vec3 &p = mesh.vertices[faces[i].v[a]], &q = mesh.vertices[faces[i].v[(a + 1) % 3]];
                const double dp = p[axis] - frame.at, dq = q[axis] - frame.at;
                if ((dp >= 0) == (dq >= 0)) continue;
                const double s = dp / (dp - dq);
                ends.push_back({p[u] + s * (q[u] - p[u]), p[v] + s * (q[v] - p[v])});
            }
            if (ends.size() == 2) segments.push_back({ends[0], ends[1]});
        }
        i = j;
    }
    return segments;
}

} // namespace tissuemesh::render::detail

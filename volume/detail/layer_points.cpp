#include "volume/detail/layer_points.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "surface/detail/rows.h"
#include "surface/detail/triangle_distance.h"
#include "surface/detail/triangle_grid.h"

namespace tissuemesh::volume::detail {
namespace {

using surface::detail::Box3;
using surface::detail::TriangleCorners;
using surface::detail::TriangleGrid;

TriangleCorners corners(const InterfaceComplex& complex, std::uint32_t t)
{
    const Triangle& tri = complex.triangles[t];
    return {complex.vertices[tri[0]], complex.vertices[tri[1]], complex.vertices[tri[2]]};
}

Box3 box_around(const Vec3& p, double radius)
{
    return {{p[0] - radius, p[1] - radius, p[2] - radius}, {p[0] + radius, p[1] + radius, p[2] + radius}};
}

/// The points kept so far, hashed by cell: finds those within a radius of a point.
class PointGrid {
public:
    explicit PointGrid(double cell_mm) : cell_mm_(cell_mm) {}

    bool any_within(const Vec3& p, double radius) const
    {
        const auto low = cell_of(p - Vec3{radius, radius, radius}), high = cell_of(p + Vec3{radius, radius, radius});
        for (std::int64_t k = low[2]; k <= high[2]; ++k)
            for (std::int64_t j = low[1]; j <= high[1]; ++j)
                for (std::int64_t i = low[0]; i <= high[0]; ++i) {
                    const auto cell = cells_.find(key({i, j, k}));
                    if (cell == cells_.end()) continue;
                    for (const Vec3& q : cell->second)
                        if (distance(p, q) < radius) return true;
                }
        return false;
    }
    void add(const Vec3& p) { cells_[key(cell_of(p))].push_back(p); }

private:
    std::array<std::int64_t, 3> cell_of(const Vec3& p) const
    {
        return {static_cast<std::int64_t>(std::floor(p[0] / cell_mm_)),
                static_cast<std::int64_t>(std::floor(p[1] / cell_mm_)),
                static_cast<std::int64_t>(std::floor(p[2] / cell_mm_))};
    }
    static std::uint64_t key(const std::array<std::int64_t, 3>& c)
    {
        // 21 bits per axis: cells of a head at any sensible size fit many times over.
        const auto part = [](std::int64_t v) { return static_cast<std::uint64_t>(v + (1 << 20)) & 0x1fffff; };
        return part(c[0]) | part(c[1]) << 21 | part(c[2]) << 42;
    }

    double cell_mm_;
    std::unordered_map<std::uint64_t, std::vector<Vec3>> cells_;
};

} // namespace

std::vector<Vec3> layer_points(const InterfaceComplex& complex, const LayerPointsOptions& options)
{
    std::vector<Vec3> points;
    if (complex.triangles.empty()) return points;
    const std::size_t vertex_count = complex.vertices.size();

    // Triangles around each vertex, and the mean edge length.
    const surface::detail::Rows around = surface::detail::star_rows(complex.triangles, vertex_count);
    double edge_sum = 0;
    for (std::uint32_t t = 0; t < complex.triangles.size(); ++t) {
        const TriangleCorners c = corners(complex, t);
        edge_sum += distance(c[0], c[1]) + distance(c[1], c[2]) + distance(c[2], c[0]);
    }
    const double mean_edge = edge_sum / static_cast<double>(3 * complex.triangles.size());

    Box3 bounds{complex.vertices.front(), complex.vertices.front()};
    for (const Vec3& v : complex.vertices)
        for (int i = 0; i < 3; ++i) {
            bounds.low[i] = std::min(bounds.low[i], v[i]);
            bounds.high[i] = std::max(bounds.high[i], v[i]);
        }
    TriangleGrid grid(bounds, 2 * mean_edge, complex.triangles.size());
    for (std::uint32_t t = 0; t < complex.triangles.size(); ++t)
        grid.insert(t, surface::detail::bounding_box(corners(complex, t)));
    PointGrid kept(options.spacing_per_edge * mean_edge);
    std::vector<std::uint32_t> near;

    for (std::uint32_t v = 0; v < vertex_count; ++v) {
        const auto star = around[v];
        if (star.empty()) continue;
        const LabelPair pair = complex.sides[star.front()];
        Vec3 normal{0, 0, 0};
        double area_sum = 0, edge_length = 0;
        bool one_pair = true;
        for (const std::uint32_t t : star) {
            if (!one_pair) break;
            const LabelPair sides = complex.sides[t];
            const TriangleCorners c = corners(complex, t);
            const Vec3 area_normal = cross(c[1] - c[0], c[2] - c[0]);
            if (sides == pair) normal = normal + area_normal;
            else if (sides.from == pair.to && sides.to == pair.from) normal = normal - area_normal;
            else one_pair = false; // a junction: no single layer on either side
            area_sum += norm(area_normal);
            for (int k = 0; k < 3; ++k)
                if (complex.triangles[t][k] == v)
                    edge_length += distance(c[k], c[(k + 1) % 3]) + distance(c[k], c[(k + 2) % 3]);
        }
        // Skip junctions and creases (triangles around the vertex facing widely different ways).
        if (!one_pair || !(norm(normal) > 0.5 * area_sum)) continue;
        normal = (1 / norm(normal)) * normal;
        const double h = edge_length / static_cast<double>(2 * star.size());
        const Vec3& origin = complex.vertices[v];

        for (const double side : {1.0, -1.0}) {
            // The right-hand normal points into `to`.
            if ((side > 0 ? pair.to : pair.from) == complex.background) continue;
            const Vec3 direction = side * normal;
            // Half the layer's thickness along the normal, where the first other triangle is met.
            const double reach = 2 * options.offset_per_edge * h;
            double thickness = std::numeric_limits<double>::infinity();
            const Vec3 end = origin + reach * direction;
            Box3 ray_box{origin, origin};
            for (int i = 0; i < 3; ++i) {
                ray_box.low[i] = std::min(origin[i], end[i]);
                ray_box.high[i] = std::max(origin[i], end[i]);
            }
            grid.query(ray_box, near);
            for (const std::uint32_t t : near) {
                const Triangle& tri = complex.triangles[t];
                if (tri[0] == v || tri[1] == v || tri[2] == v) continue;
                if (const auto hit = surface::detail::ray_meets_triangle(origin, direction, corners(complex, t), reach))
                    thickness = std::min(thickness, *hit);
            }
            const double offset = std::min(options.offset_per_edge * h, 0.5 * thickness);
            if (offset < options.min_offset_per_edge * h) continue;
            const Vec3 p = origin + offset * direction;
            // Clear of every triangle, and of the points kept before.
            const double clearance = options.clearance * offset;
            grid.query(box_around(p, clearance), near);
            const bool clear = std::none_of(near.begin(), near.end(), [&](std::uint32_t t) {
                const TriangleCorners c = corners(complex, t);
                return distance(p, surface::detail::closest_point_on_triangle(p, c)) < clearance;
            });
            if (!clear || kept.any_within(p, options.spacing_per_edge * h)) continue;
            kept.add(p);
            points.push_back(p);
        }
    }
    return points;
}

} // namespace tissuemesh::volume::detail

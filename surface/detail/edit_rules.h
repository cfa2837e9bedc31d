// Small geometric rules shared by the editor's single edits and its batch moves: index tests on
// triangles, tilt, and the gap test that keeps thin layers apart.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/interface_complex.h"
#include "surface/detail/angle_limit.h"
#include "surface/detail/cgal_intersections.h"
#include "surface/detail/mesh_measures.h"
#include "surface/detail/plane_side.h"
#include "surface/detail/triangle_distance.h"
#include "surface/detail/wedge_angle.h"

namespace tissuemesh::surface::detail {

inline bool contains(const Triangle& t, std::uint32_t v) { return t[0] == v || t[1] == v || t[2] == v; }

/// Rotates t so that it starts with v.
inline Triangle starting_at(const Triangle& t, std::uint32_t v)
{
    if (t[1] == v) return {t[1], t[2], t[0]};
    if (t[2] == v) return {t[2], t[0], t[1]};
    return t;
}

inline bool shares_vertex(const Triangle& a, const Triangle& b)
{
    return contains(b, a[0]) || contains(b, a[1]) || contains(b, a[2]);
}

/// Whether a and b use the same three vertices (triangles never repeat a vertex).
inline bool same_vertex_set(const Triangle& a, const Triangle& b)
{
    return contains(b, a[0]) && contains(b, a[1]) && contains(b, a[2]);
}

inline Vec3 normal_of(const TriangleCorners& t) { return cross(t[1] - t[0], t[2] - t[0]); }

inline double angle_between_deg(const Vec3& a, const Vec3& b)
{
    return std::atan2(norm(cross(a, b)), dot(a, b)) * 180.0 / 3.14159265358979323846;
}

/// Whether angle_between_deg(a, b) > limit.deg().
inline bool tilts_beyond(const Vec3& a, const Vec3& b, const AngleLimit& limit)
{
    const int order = limit.compare(norm(cross(a, b)), dot(a, b));
    return order != 0 ? order > 0 : angle_between_deg(a, b) > limit.deg();
}

/// The rules of a single moved triangle, now at `now` and before at `before`: degenerate or given an angle
/// below `min_angle` (and below its old one) breaks its shape; tilted beyond `max_tilt` it folds.
enum class TriangleRule : std::uint8_t { none, shape, tilt };
inline TriangleRule single_triangle_rule(const TriangleCorners& now, const TriangleCorners& before,
                                         const AngleLimit& min_angle, const AngleLimit& max_tilt)
{
    if (are_collinear(now[0], now[1], now[2])) return TriangleRule::shape;
    if (has_angle_below(now, min_angle) && smallest_angle_deg(now) < smallest_angle_deg(before) - 1e-9)
        return TriangleRule::shape;
    if (tilts_beyond(normal_of(now), normal_of(before), max_tilt)) return TriangleRule::tilt;
    return TriangleRule::none;
}

/// A cheap sufficient test for distance(a, b) > gap: the bounding spheres around the centroids are apart.
inline bool farther_than(const TriangleCorners& a, const TriangleCorners& b, double gap)
{
    const Vec3 ca = (1.0 / 3.0) * (a[0] + a[1] + a[2]), cb = (1.0 / 3.0) * (b[0] + b[1] + b[2]);
    double ra = 0, rb = 0;
    for (int k = 0; k < 3; ++k) {
        ra = std::max(ra, distance(a[k], ca));
        rb = std::max(rb, distance(b[k], cb));
    }
    return distance(ca, cb) - ra - rb > gap;
}

/// Whether triangle `now` (formerly `before`) comes closer than `gap` to `other` (formerly
/// `other_before`), vertex to face, where it was not that close before. A vertex further than the gap
/// from the plane of the face is further from the face: its closest point is not computed (the margin
/// is far above the rounding of either distance, so the answer is the same).
inline bool closes_gap(const TriangleCorners& now, const TriangleCorners& before, const TriangleCorners& other,
                       const TriangleCorners& other_before, double gap)
{
    const Vec3 n_now = normal_of(now), n_other = normal_of(other);
    const double safe = gap * (1 + 1e-6) + 1e-9;
    const double reach_now = safe * norm(n_now), reach_other = safe * norm(n_other);
    for (int k = 0; k < 3; ++k) {
        if (!(std::abs(dot(now[k] - other[0], n_other)) > reach_other)) {
            const double d = distance(now[k], closest_point_on_triangle(now[k], other));
            if (d < gap && d < distance(before[k], closest_point_on_triangle(before[k], other_before)) - 1e-12)
                return true;
        }
        if (!(std::abs(dot(other[k] - now[0], n_now)) > reach_now)) {
            const double e = distance(other[k], closest_point_on_triangle(other[k], now));
            if (e < gap && e < distance(other_before[k], closest_point_on_triangle(other_before[k], before)) - 1e-12)
                return true;
        }
    }
    return false;
}

/// Whether triangles `a` and `b`, sharing one vertex, now open a wedge thinner than `limit_deg` there and
/// thinner than before (`before_a`, `before_b`: their corners before the edit; none when `a` is new, and
/// then any wedge under the limit counts).
inline bool closes_wedge(const Triangle& a, const TriangleCorners& now_a, const TriangleCorners* before_a,
                         const Triangle& b, const TriangleCorners& now_b, const TriangleCorners& before_b,
                         double limit_deg)
{
    if (wedge_certainly_open(a, now_a, b, now_b, limit_deg)) return false;
    const std::optional<double> now = wedge_between(a, now_a, b, now_b);
    if (!now || *now >= limit_deg) return false;
    return before_a == nullptr || *now < *wedge_between(a, *before_a, b, before_b) - 1e-9;
}

} // namespace tissuemesh::surface::detail

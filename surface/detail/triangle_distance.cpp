#include "surface/detail/triangle_distance.h"

#include <algorithm>
#include <cmath>

namespace tissuemesh::surface::detail {

Vec3 closest_point_on_segment(const Vec3& p, const Vec3& a, const Vec3& b)
{
    const Vec3 ab = b - a;
    const double length2 = dot(ab, ab);
    if (length2 <= 0) return a;
    const double s = std::clamp(dot(p - a, ab) / length2, 0.0, 1.0);
    return a + s * ab;
}

Vec3 closest_point_on_triangle(const Vec3& p, const TriangleCorners& t)
{
    // Project onto the plane; if the projection falls inside (all barycentric weights >= 0) it is the
    // answer, otherwise the nearest point lies on one of the edges.
    const Vec3 e0 = t[1] - t[0], e1 = t[2] - t[0];
    const Vec3 n = cross(e0, e1);
    const double area2 = dot(n, n);
    if (area2 > 0) {
        const Vec3 q = p - (dot(p - t[0], n) / area2) * n;
        const double w2 = dot(cross(e0, q - t[0]), n) / area2;
        const double w1 = dot(cross(q - t[0], e1), n) / area2;
        if (w1 >= 0 && w2 >= 0 && w1 + w2 <= 1) return q;
    }
    Vec3 best = closest_point_on_segment(p, t[0], t[1]);
    for (int k = 1; k < 3; ++k) {
        const Vec3 c = closest_point_on_segment(p, t[k], t[(k + 1) % 3]);
        if (distance(p, c) < distance(p, best)) best = c;
    }
    return best;
}

double segment_distance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1)
{
    // Minimise |p0 + s d1 - q0 - t d2| over the unit square: the unconstrained optimum clamped, then
    // each parameter re-optimised for the other's clamped value; end-point distances cover the rest.
    const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r), c = dot(d1, r), b = dot(d1, d2);
    const double denominator = a * e - b * b;
    double best = std::min(
        {distance(p0, closest_point_on_segment(p0, q0, q1)), distance(p1, closest_point_on_segment(p1, q0, q1)),
         distance(q0, closest_point_on_segment(q0, p0, p1)), distance(q1, closest_point_on_segment(q1, p0, p1))});
    if (a > 0 && e > 0 && denominator > 1e-18 * a * e) {
        const double s = std::clamp((b * f - c * e) / denominator, 0.0, 1.0);
        const double t = std::clamp((b * s + f) / e, 0.0, 1.0);
        const double s2 = std::clamp((t * b - c) / a, 0.0, 1.0);
        best = std::min(best, distance(p0 + s2 * d1, q0 + t * d2));
    }
    return best;
}

double triangle_distance(const TriangleCorners& a, const TriangleCorners& b)
{
    double best = distance(a[0], closest_point_on_triangle(a[0], b));
    for (int k = 0; k < 3; ++k) {
        best = std::min(best, distance(a[k], closest_point_on_triangle(a[k], b)));
        best = std::min(best, distance(b[k], closest_point_on_triangle(b[k], a)));
        for (int m = 0; m < 3; ++m) best = std::min(best, segment_distance(a[k], a[(k + 1) % 3], b[m], b[(m + 1) % 3]));
    }
    return best;
}

std::optional<double> ray_meets_triangle(const Vec3& o, const Vec3& d, const TriangleCorners& c, double reach)
{
    const Vec3 e1 = c[1] - c[0], e2 = c[2] - c[0];
    const Vec3 p = cross(d, e2);
    const double det = dot(e1, p);
    if (std::abs(det) < 1e-14 * dot(e1, e1)) return std::nullopt; // parallel to the plane
    const Vec3 s = o - c[0];
    const double u = dot(s, p) / det;
    if (u < 0 || u > 1) return std::nullopt;
    const Vec3 q = cross(s, e1);
    const double v = dot(d, q) / det;
    if (v < 0 || u + v > 1) return std::nullopt;
    const double t = dot(e2, q) / det;
    if (!(t > 0 && t <= reach)) return std::nullopt;
    return t;
}

} // namespace tissuemesh::surface::detail

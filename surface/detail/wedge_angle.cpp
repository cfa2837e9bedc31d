#include "surface/detail/wedge_angle.h"

#include <algorithm>
#include <cmath>

namespace tissuemesh::surface::detail {
namespace {

constexpr double degrees_per_radian = 180.0 / 3.14159265358979323846;

Vec3 unit(const Vec3& v)
{
    const double length = norm(v);
    return length > 0 ? (1.0 / length) * v : v;
}

double angle_rad(const Vec3& u, const Vec3& v) { return std::atan2(norm(cross(u, v)), dot(u, v)); }

/// Whether unit vector `p` in the plane of the arc from `a` to `b` (normal `n` = a x b) lies on that arc.
bool on_arc(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& n)
{
    return dot(cross(a, p), n) >= 0 && dot(cross(p, b), n) >= 0;
}

/// Spherical distance (radians) from unit vector `p` to the shorter great-circle arc between unit
/// vectors `a` and `b`: to the arc's interior when p projects onto it, else to the nearer end.
double point_to_arc(const Vec3& p, const Vec3& a, const Vec3& b)
{
    const Vec3 n = cross(a, b);
    const double length = norm(n);
    if (length > 0) {
        const Vec3 m = (1.0 / length) * n;
        const double height = dot(p, m);
        const Vec3 in_plane = p - height * m;
        if (norm(in_plane) > 0 && on_arc(in_plane, a, b, m)) return std::atan2(std::abs(height), norm(in_plane));
    }
    return std::min(angle_rad(p, a), angle_rad(p, b));
}

/// Whether the arcs a1a2 and b1b2 (unit vectors, each shorter than a half circle) cross.
bool arcs_cross(const Vec3& a1, const Vec3& a2, const Vec3& b1, const Vec3& b2)
{
    const Vec3 na = cross(a1, a2), nb = cross(b1, b2);
    if (!(dot(b1, na) * dot(b2, na) < 0 && dot(a1, nb) * dot(a2, nb) < 0)) return false;
    // Arcs on one great circle (opposite triangles of a flat fan: b = -a exactly) have no crossing line; the
    // zero vector is on every arc by on_arc()'s test, so it would say they cross. Overlapping arcs on one
    // circle are found by the distances instead.
    const Vec3 across = cross(na, nb);
    if (!(norm(across) > 0)) return false;
    const Vec3 line = unit(across);
    for (const double sign : {1.0, -1.0}) {
        const Vec3 p = sign * line;
        if (on_arc(p, a1, a2, na) && on_arc(p, b1, b2, nb)) return true;
    }
    return false;
}

} // namespace

double wedge_angle_deg(const Vec3& apex, const Vec3& a1, const Vec3& a2, const Vec3& b1, const Vec3& b2)
{
    const Vec3 u1 = unit(a1 - apex), u2 = unit(a2 - apex), v1 = unit(b1 - apex), v2 = unit(b2 - apex);
    if (arcs_cross(u1, u2, v1, v2)) return 0;
    const double closest = std::min(
        {point_to_arc(v1, u1, u2), point_to_arc(v2, u1, u2), point_to_arc(u1, v1, v2), point_to_arc(u2, v1, v2)});
    return closest * degrees_per_radian;
}

std::optional<int> single_shared_corner(const Triangle& a, const Triangle& b)
{
    std::optional<int> shared;
    for (int k = 0; k < 3; ++k) {
        if (b[0] != a[k] && b[1] != a[k] && b[2] != a[k]) continue;
        if (shared) return std::nullopt;
        shared = k;
    }
    return shared;
}

std::optional<double> wedge_between(const Triangle& a, const TriangleCorners& ca, const Triangle& b,
                                    const TriangleCorners& cb)
{
    const std::optional<int> i = single_shared_corner(a, b);
    if (!i) return std::nullopt;
    const int j = b[0] == a[*i] ? 0 : b[1] == a[*i] ? 1 : 2;
    return wedge_angle_deg(ca[*i], ca[(*i + 1) % 3], ca[(*i + 2) % 3], cb[(j + 1) % 3], cb[(j + 2) % 3]);
}

bool wedge_certainly_open(const Triangle& a, const TriangleCorners& ca, const Triangle& b, const TriangleCorners& cb,
                          double limit_deg)
{
    if (!(limit_deg > 0 && limit_deg < 89)) return false;
    const std::optional<int> i = single_shared_corner(a, b);
    if (!i) return false;
    const int j = b[0] == a[*i] ? 0 : b[1] == a[*i] ? 1 : 2;
    const Vec3& apex = ca[*i];
    const Vec3 u1 = unit(ca[(*i + 1) % 3] - apex), u2 = unit(ca[(*i + 2) % 3] - apex);
    const Vec3 v1 = unit(cb[(j + 1) % 3] - apex), v2 = unit(cb[(j + 2) % 3] - apex);
    // Unit directions from the apex; the sine of the limit, raised far above the rounding of these sums.
    const double reach = std::sin(limit_deg / degrees_per_radian) * (1 + 1e-6) + 1e-12;
    // Both points beyond `reach` on one side of the plane with unit normal m (through the apex).
    const auto beyond = [&](const Vec3& m, const Vec3& p, const Vec3& q, double side) {
        return side * dot(p, m) > reach && side * dot(q, m) > reach;
    };
    const auto one_side = [&](const Vec3& m, const Vec3& p, const Vec3& q) {
        return beyond(m, p, q, 1) || beyond(m, p, q, -1);
    };
    const Vec3 na = unit(cross(u1, u2)), nb = unit(cross(v1, v2));
    if (norm(na) > 0 && one_side(na, v1, v2)) return true;
    if (norm(nb) > 0 && one_side(nb, u1, u2)) return true;
    // The plane between the arcs' middles: one arc beyond it on each side.
    const Vec3 s = unit(unit(u1 + u2) - unit(v1 + v2));
    return norm(s) > 0 && beyond(s, u1, u2, 1) && beyond(s, v1, v2, -1);
}

} // namespace tissuemesh::surface::detail

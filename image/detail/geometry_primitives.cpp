#include "image/detail/geometry_primitives.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tissuemesh::image::detail {

double distance_to_sphere(const Vec3& p, const Vec3& centre, double radius)
{
    return std::abs(distance(p, centre) - radius);
}

namespace {

/// Distance from the point at height h above a plane and at distance r_perp from the axis to the
/// circle of `radius` in that plane around the axis.
double distance_to_circle(double h, double r_perp, double radius) { return std::hypot(r_perp - radius, h); }

} // namespace

double distance_to_hemisphere(const Vec3& p, const Vec3& centre, double radius, const Vec3& normal)
{
    const Vec3 q = p - centre;
    const double h = dot(q, normal);
    // The nearest point of the whole sphere is the radial projection; when it lies on the kept half it
    // is the answer, otherwise the nearest point of the half lies on its rim (the great circle).
    if (h <= 0) return std::abs(norm(q) - radius);
    return distance_to_circle(h, norm(q - h * normal), radius);
}

double distance_to_disk(const Vec3& p, const Vec3& centre, double radius, const Vec3& normal)
{
    const Vec3 q = p - centre;
    const double h = dot(q, normal);
    const double r_perp = norm(q - h * normal);
    return r_perp <= radius ? std::abs(h) : distance_to_circle(h, r_perp, radius);
}

double distance_to_rect(const Vec3& p, const AxisRect& rect)
{
    const int u = (rect.axis + 1) % 3, v = (rect.axis + 2) % 3;
    const int first = std::min(u, v), second = std::max(u, v);
    const double du = std::max({rect.lo[0] - p[first], 0.0, p[first] - rect.hi[0]});
    const double dv = std::max({rect.lo[1] - p[second], 0.0, p[second] - rect.hi[1]});
    const double dn = p[rect.axis] - rect.coordinate;
    return std::sqrt(du * du + dv * dv + dn * dn);
}

std::vector<AxisRect> box_faces(const Vec3& lo, const Vec3& hi)
{
    std::vector<AxisRect> faces;
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        const int first = std::min(u, v), second = std::max(u, v);
        for (const double c : {lo[axis], hi[axis]})
            faces.push_back({axis, c, {lo[first], lo[second]}, {hi[first], hi[second]}});
    }
    return faces;
}

std::vector<AxisRect> subtract_rect(const AxisRect& rect, const AxisRect& hole)
{
    // Clip the hole to the rectangle, then cut the rest into bands: below and above the hole along the
    // second in-plane axis (full width), left and right of it within the hole's band.
    const double u0 = std::max(rect.lo[0], hole.lo[0]), u1 = std::min(rect.hi[0], hole.hi[0]);
    const double v0 = std::max(rect.lo[1], hole.lo[1]), v1 = std::min(rect.hi[1], hole.hi[1]);
    if (u0 >= u1 || v0 >= v1) return {rect};
    std::vector<AxisRect> pieces;
    const auto add = [&](double a0, double b0, double a1, double b1) {
        if (a1 > a0 && b1 > b0) pieces.push_back({rect.axis, rect.coordinate, {a0, b0}, {a1, b1}});
    };
    add(rect.lo[0], rect.lo[1], rect.hi[0], v0);
    add(rect.lo[0], v1, rect.hi[0], rect.hi[1]);
    add(rect.lo[0], v0, u0, v1);
    add(u1, v0, rect.hi[0], v1);
    return pieces;
}

namespace {

/// The Lagrange multiplier t > -e[n-1]^2 of the closest point, for y[n-1] > 0: the root of
/// F(t) = sum_i (e_i y_i / (t + e_i^2))^2 - 1, strictly decreasing on that interval.
double solve_multiplier(const double* e, const double* y, int n)
{
    const int m = n - 1;
    double scaled = 0;
    for (int i = 0; i < n; ++i) scaled += (e[i] * y[i]) * (e[i] * y[i]);
    // At lo the shortest axis' term alone is 1 (F >= 0); at hi every denominator exceeds the norm (F <= 0).
    double lo = -e[m] * e[m] + e[m] * y[m];
    double hi = -e[m] * e[m] + std::sqrt(scaled);
    for (int iteration = 0; iteration < 2000; ++iteration) {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        double f = -1;
        for (int i = 0; i < n; ++i) {
            const double r = e[i] * y[i] / (mid + e[i] * e[i]);
            f += r * r;
        }
        (f > 0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

/// Distance to the ellipsoid with semi-axes e (descending) from y (every y_i >= 0), in n dimensions.
double distance_sorted(const double* e, const double* y, int n)
{
    if (n == 1) return std::abs(y[0] - e[0]);
    const int m = n - 1;
    if (y[m] > 0) {
        const double t = solve_multiplier(e, y, n);
        double d2 = 0;
        for (int i = 0; i < n; ++i) {
            const double x = e[i] * e[i] * y[i] / (t + e[i] * e[i]);
            d2 += (x - y[i]) * (x - y[i]);
        }
        return std::sqrt(d2);
    }
    // y on the plane of the two longer axes: the closest point lies either in that plane (an ellipse
    // problem) or off it, where the multiplier is exactly -e_m^2.
    double best = distance_sorted(e, y, m);
    double sum = 0, d2 = 0;
    for (int i = 0; i < m; ++i) {
        if (y[i] == 0) continue;
        if (e[i] <= e[m]) return best;
        const double x = e[i] * e[i] * y[i] / (e[i] * e[i] - e[m] * e[m]);
        sum += (x / e[i]) * (x / e[i]);
        d2 += (x - y[i]) * (x - y[i]);
    }
    if (sum < 1) best = std::min(best, std::sqrt(d2 + e[m] * e[m] * (1 - sum)));
    return best;
}

} // namespace

double distance_to_ellipsoid(const std::array<double, 3>& semi_axes, const Vec3& local)
{
    std::array<int, 3> order{0, 1, 2};
    std::sort(order.begin(), order.end(), [&](int a, int b) { return semi_axes[a] > semi_axes[b]; });
    double e[3], y[3];
    for (int i = 0; i < 3; ++i) {
        e[i] = semi_axes[order[i]];
        y[i] = std::abs(local[order[i]]); // the ellipsoid is symmetric in every axis
    }
    return distance_sorted(e, y, 3);
}

std::vector<Vec3> unit_sphere_points(std::size_t count)
{
    count = std::max<std::size_t>(count, 2);
    const double golden_angle = std::numbers::pi * (3.0 - std::sqrt(5.0));
    std::vector<Vec3> points;
    points.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
        const double z = 1.0 - (2.0 * static_cast<double>(i) + 1.0) / static_cast<double>(count);
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        const double phi = golden_angle * static_cast<double>(i);
        points.push_back({r * std::cos(phi), r * std::sin(phi), z});
    }
    return points;
}

void sample_rect(const AxisRect& rect, double spacing_mm, std::vector<Vec3>& points)
{
    const int u = (rect.axis + 1) % 3, v = (rect.axis + 2) % 3;
    const int first = std::min(u, v), second = std::max(u, v);
    const auto steps = [&](int k) {
        return std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil((rect.hi[k] - rect.lo[k]) / spacing_mm)));
    };
    const std::size_t nu = steps(0), nv = steps(1);
    for (std::size_t a = 0; a <= nu; ++a) {
        for (std::size_t b = 0; b <= nv; ++b) {
            Vec3 p;
            p[rect.axis] = rect.coordinate;
            p[first] = rect.lo[0] + (rect.hi[0] - rect.lo[0]) * static_cast<double>(a) / static_cast<double>(nu);
            p[second] = rect.lo[1] + (rect.hi[1] - rect.lo[1]) * static_cast<double>(b) / static_cast<double>(nv);
            points.push_back(p);
        }
    }
}

} // namespace tissuemesh::image::detail

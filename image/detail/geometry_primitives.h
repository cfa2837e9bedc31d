// Exact distances to, and samples on, the analytic surfaces phantoms are built from. Internal to image/.
#pragma once

#include <array>
#include <vector>

#include "core/vec3.h"

namespace tissuemesh::image::detail {

/// Distance from `p` to the sphere |x - centre| = radius.
double distance_to_sphere(const Vec3& p, const Vec3& centre, double radius);

/// Distance from `p` to the closed half of the sphere |x - centre| = radius where
/// dot(x - centre, normal) <= 0 (`normal` is a unit vector).
double distance_to_hemisphere(const Vec3& p, const Vec3& centre, double radius, const Vec3& normal);

/// Distance from `p` to the disk of `radius` around `centre` in the plane with unit `normal`.
double distance_to_disk(const Vec3& p, const Vec3& centre, double radius, const Vec3& normal);

/// An axis-aligned rectangle in the plane x[axis] == coordinate, spanning [lo, hi] along the two other
/// axes (in increasing axis order).
struct AxisRect {
    int axis = 0;
    double coordinate = 0;
    std::array<double, 2> lo{0, 0};
    std::array<double, 2> hi{0, 0};
};

double distance_to_rect(const Vec3& p, const AxisRect& rect);

/// The six faces of the box [lo, hi].
std::vector<AxisRect> box_faces(const Vec3& lo, const Vec3& hi);

/// `rect` minus the open interior of `hole` (same plane): up to four rectangles covering the rest.
std::vector<AxisRect> subtract_rect(const AxisRect& rect, const AxisRect& hole);

/// Distance from `local` to the ellipsoid sum (x_i / semi_axes_i)^2 = 1 (axis-aligned, centred at 0).
/// Robust for points inside, outside, on the axes and at the centre: the closest point is found from
/// its Lagrange condition x_i = e_i^2 y_i / (t + e_i^2) by bisection on t, with the degenerate cases
/// (a zero coordinate along the shortest axis) reduced to the ellipse of one dimension less.
double distance_to_ellipsoid(const std::array<double, 3>& semi_axes, const Vec3& local);

/// About `count` points spread evenly over the unit sphere (a Fibonacci spiral), deterministic.
std::vector<Vec3> unit_sphere_points(std::size_t count);

/// Points on `rect` on a grid about `spacing_mm` apart, edges included.
void sample_rect(const AxisRect& rect, double spacing_mm, std::vector<Vec3>& points);

} // namespace tissuemesh::image::detail

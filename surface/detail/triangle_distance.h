// Euclidean distances between points, segments and triangles (double precision), for gap checks and
// projections onto a reference surface, and rays against triangles, for measures (layer thickness, which side of a
// surface a voxel centre is on). Not exact: callers compare against tolerances, never zero.
#pragma once

#include <array>
#include <optional>

#include "core/vec3.h"

namespace tissuemesh::surface::detail {

using TriangleCorners = std::array<Vec3, 3>;

/// The point of triangle `t` (closed) nearest to `p`. Works for degenerate triangles too.
Vec3 closest_point_on_triangle(const Vec3& p, const TriangleCorners& t);

/// The point of segment ab nearest to `p`.
Vec3 closest_point_on_segment(const Vec3& p, const Vec3& a, const Vec3& b);

/// Distance between the closed segments p0p1 and q0q1.
double segment_distance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);

/// Distance between two closed triangles, assuming they do not intersect (then the minimum is attained
/// at a vertex of one of them or between two edges).
double triangle_distance(const TriangleCorners& a, const TriangleCorners& b);

/// Where the ray from o along unit d first meets triangle c, beyond o and within `reach` (Moller and Trumbore
/// 1997); none for a ray parallel to the triangle's plane.
std::optional<double> ray_meets_triangle(const Vec3& o, const Vec3& d, const TriangleCorners& c, double reach);

} // namespace tissuemesh::surface::detail

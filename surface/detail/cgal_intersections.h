// Exact geometric predicates for the surface checker, behind a plain C++ interface: every CGAL type
// stays in cgal_intersections.cpp (a CGAL translation unit takes a minute to compile).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "core/interface_complex.h"
#include "core/vec3.h"

namespace tissuemesh::surface::detail {

/// Two triangle indices, first < second.
using TrianglePair = std::pair<std::uint32_t, std::uint32_t>;

/// True when the three points lie on one line (or coincide); exact.
bool are_collinear(const Vec3& a, const Vec3& b, const Vec3& c);

/// Sign of dot((b - a) x (c - a), d - a), exact: +1 when d lies on the side of the plane abc its
/// right-hand normal points to, -1 on the other side, 0 in the plane.
int orientation(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// The pairs among `candidates` (indices into `triangles`) whose triangles meet anywhere other than
/// at the vertices and edges they share by index; sorted ascending. Exact predicates throughout.
/// Shared vertices are recognised by index only: give `triangles` with coincident vertices already
/// merged to one index. Triangles sharing all three indices are skipped (the caller reports them as
/// duplicates).
/// @pre every candidate is non-degenerate (are_collinear() false) and indexes into `vertices`
std::vector<TrianglePair> find_intersecting_pairs(const std::vector<Vec3>& vertices,
                                                  const std::vector<Triangle>& triangles,
                                                  const std::vector<std::uint32_t>& candidates);

/// Whether triangles `a` and `b` (indices into `vertices`) meet anywhere other than at the vertices and
/// edge they share by index; exact. The local test behind find_intersecting_pairs(), for editors that
/// check each change where it happens.
/// @pre both non-degenerate (are_collinear() false) and not on the same three vertices
bool triangles_intersect(const std::vector<Vec3>& vertices, const Triangle& a, const Triangle& b);

/// A point of the intersection of two triangles (the centroid of the intersection, rounded), or the
/// midpoint of their centroids when they do not intersect. For locating defects in messages.
Vec3 intersection_point(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b);

} // namespace tissuemesh::surface::detail

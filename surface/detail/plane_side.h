// The side of a plane a point is on, in floating point, answered only when certain, and the test of two
// triangles built on it: the shortcut in front of the exact predicates, shared by the surface checker and
// the editor.
#pragma once

#include "core/interface_complex.h"
#include "surface/detail/triangle_distance.h"

namespace tissuemesh::surface::detail {

/// Sign of orient3d(a, b, c, d) when certain: +1, -1, or 0 for unsure. Certain means the determinant
/// exceeds 1e-10 of the product of the lengths it multiplies, far above the rounding of its few operations.
inline int certain_side(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
    constexpr double margin = 1e-10;
    const Vec3 u = b - a, v = c - a, w = d - a;
    const double det = dot(cross(u, v), w);
    const double scale2 = dot(u, u) * dot(v, v) * dot(w, w);
    return det * det > margin * margin * scale2 ? (det > 0 ? 1 : -1) : 0;
}

/// Whether triangles a and b (corners pa, pb) certainly meet only at the vertices and edge they share (if
/// any): the vertices of one that the other lacks lie strictly on one side of the other's plane (certain
/// in floating point: certain_side()). False when unsure; the exact test then decides. Most pairs of a
/// smooth surface are decided here, at a fraction of the exact test's cost.
inline bool certainly_apart(const Triangle& a, const TriangleCorners& pa, const Triangle& b, const TriangleCorners& pb)
{
    // The corners of `q` missing from `of`, all certainly on one side of the plane of `plane`.
    const auto off_plane = [](const TriangleCorners& plane, const Triangle& q, const TriangleCorners& pq,
                              const Triangle& of) {
        int side = 0;
        for (int k = 0; k < 3; ++k) {
            if (q[k] == of[0] || q[k] == of[1] || q[k] == of[2]) continue;
            const int s = certain_side(plane[0], plane[1], plane[2], pq[k]);
            if (s == 0 || (side != 0 && s != side)) return false;
            side = s;
        }
        return side != 0;
    };
    return off_plane(pa, b, pb, a) || off_plane(pb, a, pa, b);
}

} // namespace tissuemesh::surface::detail

// The side of a plane a point is on, in floating point, answered only when certain: the shortcut in front
// of the exact predicates, shared by the surface checker and the editor's batch judgements.
#pragma once

#include "core/vec3.h"

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

} // namespace tissuemesh::surface::detail

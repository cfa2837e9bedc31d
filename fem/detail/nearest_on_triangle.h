// The point of a triangle nearest a given point, for electrodes on the surface and distances to interfaces.
#pragma once

#include <array>

#include "core/vec3.h"

namespace tissuemesh::fem::detail {

// The point of triangle abc nearest p, as barycentric weights of a, b, c (Ericson, Real-Time Collision
// Detection, 5.1.5: the Voronoi regions of the corners, then of the edges, then the face).
inline std::array<double, 3> nearest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
    const Vec3 bp = p - b;
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const double v = d1 / (d1 - d3);
        return {1 - v, v, 0};
    }
    const Vec3 cp = p - c;
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const double w = d2 / (d2 - d6);
        return {1 - w, 0, w};
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {0, 1 - w, w};
    }
    const double denominator = va + vb + vc;
    if (!(denominator > 0)) return {1, 0, 0}; // a degenerate triangle: its first corner
    const double v = vb / denominator, w = vc / denominator;
    return {1 - v - w, v, w};
}

} // namespace tissuemesh::fem::detail

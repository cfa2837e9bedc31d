// Small measures of interface complexes shared by the surface steps.
#pragma once

#include "core/interface_complex.h"
#include "surface/detail/angle_limit.h"
#include "surface/detail/triangle_distance.h"

namespace tissuemesh::surface::detail {

/// Mean length of the triangles' first edges (a cheap estimate of the typical edge), mm; 1 when empty.
double mean_edge_length(const InterfaceComplex& complex);

/// Smallest interior angle of a triangle, degrees (0 for a degenerate one).
double smallest_angle_deg(const TriangleCorners& corners);

/// Whether smallest_angle_deg(t) < limit.deg() (as that function computes it), mostly without atan2.
inline bool has_angle_below(const TriangleCorners& t, const AngleLimit& limit)
{
    bool unsure = false;
    for (int k = 0; k < 3; ++k) {
        const Vec3 u = t[(k + 1) % 3] - t[k], w = t[(k + 2) % 3] - t[k];
        const int order = limit.compare(norm(cross(u, w)), dot(u, w));
        if (order < 0) return true;
        unsure = unsure || order == 0;
    }
    return unsure && smallest_angle_deg(t) < limit.deg();
}

} // namespace tissuemesh::surface::detail

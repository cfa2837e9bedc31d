// Small geometric helpers of LocalEditor's two files (local_editor.cpp, local_edits.cpp).
#pragma once

#include <algorithm>

#include "core/interface_complex.h"
#include "surface/detail/triangle_distance.h"

namespace tissuemesh::surface::detail {

inline bool has(const Triangle& t, std::uint32_t v) { return t[0] == v || t[1] == v || t[2] == v; }

inline bool share_vertex(const Triangle& a, const Triangle& b) { return has(b, a[0]) || has(b, a[1]) || has(b, a[2]); }

/// Cosine of a triangle's smallest angle (1 for a degenerate triangle).
inline double smallest_angle_cosine(const TriangleCorners& p)
{
    double best = -1;
    for (int k = 0; k < 3; ++k) {
        const Vec3 u = p[(k + 1) % 3] - p[k], v = p[(k + 2) % 3] - p[k];
        const double lengths = norm(u) * norm(v);
        best = std::max(best, lengths > 0 ? dot(u, v) / lengths : 1.0);
    }
    return best;
}

} // namespace tissuemesh::surface::detail

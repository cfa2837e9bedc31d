// The integral of a vector field over a tet near a singular point: a fixed rule on midpoint children.
#pragma once

#include <algorithm>
#include <array>

#include "core/vec3.h"

namespace tissuemesh::fem::detail {

/// The integral of `field` (a callable Vec3 -> Vec3) over the tet `c` of volume `volume`: the 4-point
/// degree-2 rule, applied to the 8 midpoint children (each of volume / 8) while the tet's longest edge
/// exceeds `split_ratio` times its centre's distance to `near` (the field's singular point), at most
/// `max_splits` times. Children are summed in a fixed order: the same bytes on every run.
template <typename Field>
Vec3 adaptive_tet_integral(const std::array<Vec3, 4>& c, double volume, const Vec3& near, double split_ratio,
                           int max_splits, const Field& field, int depth = 0)
{
    const Vec3 centre = 0.25 * (c[0] + c[1] + c[2] + c[3]);
    double longest = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) longest = std::max(longest, distance(c[i], c[j]));
    if (depth >= max_splits || longest <= split_ratio * distance(centre, near)) {
        constexpr double a = 0.5854101966249685, b = 0.1381966011250105;
        Vec3 sum{0, 0, 0};
        for (int k = 0; k < 4; ++k) {
            Vec3 point{0, 0, 0};
            for (int i = 0; i < 4; ++i) point = point + (i == k ? a : b) * c[i];
            sum = sum + field(point);
        }
        return (volume / 4) * sum;
    }
    const auto mid = [&](int i, int j) { return 0.5 * (c[i] + c[j]); };
    const Vec3 m01 = mid(0, 1), m02 = mid(0, 2), m03 = mid(0, 3), m12 = mid(1, 2), m13 = mid(1, 3), m23 = mid(2, 3);
    const std::array<std::array<Vec3, 4>, 8> children{{{c[0], m01, m02, m03},
                                                       {m01, c[1], m12, m13},
                                                       {m02, m12, c[2], m23},
                                                       {m03, m13, m23, c[3]},
                                                       {m01, m02, m03, m13},
                                                       {m01, m02, m12, m13},
                                                       {m02, m03, m13, m23},
                                                       {m02, m12, m13, m23}}};
    Vec3 sum{0, 0, 0};
    for (const auto& child : children)
        sum = sum + adaptive_tet_integral(child, volume / 8, near, split_ratio, max_splits, field, depth + 1);
    return sum;
}

} // namespace tissuemesh::fem::detail

// A plain C++ face to TetGen: arrays in, arrays out, no tetgen.h outside tetgen_adapter.cpp.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace tissuemesh::volume::detail {

struct TetgenRegion {
    std::array<double, 3> seed; ///< a point strictly inside the region
    int attribute = 0;          ///< region attribute (our tissue label)
    double max_volume = -1;     ///< volume bound; negative: none
};

struct TetgenInput {
    std::vector<double> points;                ///< 3 per point
    std::vector<std::array<int, 3>> triangles; ///< one facet each; marker = index + 1
    std::vector<TetgenRegion> regions;
    std::string switches; ///< e.g. "pYzQnnq2/5O2"
};

struct TetgenOutput {
    std::vector<double> points; ///< 3 per point; input points come first, unchanged
    std::vector<std::array<int, 4>> tets;
    std::vector<double> tet_attributes;    ///< one per tet when regions were given
    std::vector<std::array<int, 3>> faces; ///< subfaces (on input triangles)
    std::vector<int> face_markers;         ///< input triangle index + 1
};

/// The exact sign of dot(d - a, cross(b - a, c - a)), by TetGen's robust orient3d: +1 when d lies on the
/// side the right-hand normal of (a, b, c) points to, -1 on the other side, 0 when the four are coplanar.
/// Exact where the same expression in doubles is not: for nearly flat tets its rounding can flip the sign.
int exact_side(const std::array<double, 3>& a, const std::array<double, 3>& b, const std::array<double, 3>& c,
               const std::array<double, 3>& d);

/// Runs TetGen in a child process (see isolated_call.h), and `meanwhile` (when given) in this one while it
/// runs. TetGen's own printing is captured, not shown.
/// @throws AlgorithmError with TetGen's diagnosis (its error code explained, its last message lines),
///         also when TetGen crashed or aborted on an assertion
TetgenOutput run_tetgen(const TetgenInput& input, const std::function<void()>& meanwhile = {});

} // namespace tissuemesh::volume::detail

// How extract_interfaces() tetrahedralizes a grid cube: the 6 Kuhn tetrahedra, or under the thin-tissue
// priority rule (see ExtractOptions::priority) which diagonal each cube face uses and whether the cube is
// split into 12 tetrahedra around a centre point. The extraction and surface::ExtractedTissue both take a
// cube's tetrahedra from cube_tetrahedra(), so they cannot disagree about them.
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <vector>

#include "core/label_image.h"

namespace tissuemesh::surface::detail {

/// The 6 faces of a grid cube as corner cycles {c00, c10, c11, c01} (corner bits: 0 +x, 1 +y, 2 +z);
/// c00 is the face's lowest corner and c11 its highest, so c00-c11 is the Kuhn diagonal and c10-c01 the
/// other one.
constexpr std::array<std::array<int, 4>, 6> cube_faces{{
    {0, 2, 6, 4},
    {1, 3, 7, 5},
    {0, 1, 5, 4},
    {2, 3, 7, 6},
    {0, 1, 3, 2},
    {4, 5, 7, 6},
}};

/// A tetrahedron of a cube as cube vertices: corners 0-7 (bit 0: +x, bit 1: +y, bit 2: +z) and the centre, 8.
using CubeTet = std::array<int, 4>;

/// The 6 Kuhn tetrahedra of a cube, as chains of cube corners: every tetrahedron runs from corner 0 to corner
/// 7 adding one axis at a time, so each corner is a subset of the next and every tetrahedron edge goes in a
/// non-negative grid direction. The tetrahedron holding a point of the cube is the one whose axes, in chain
/// order, are the point's axes by decreasing fraction.
constexpr std::array<CubeTet, 6> kuhn_tets{{
    {0, 1, 3, 7},
    {0, 1, 5, 7},
    {0, 2, 3, 7},
    {0, 2, 6, 7},
    {0, 4, 5, 7},
    {0, 4, 6, 7},
}};

/// How one cube is tetrahedralized.
struct CubePlan {
    bool split = false;         ///< 12 tetrahedra around the cube centre instead of the 6 Kuhn ones
    std::array<bool, 6> anti{}; ///< face f (cube_faces order) uses its c10-c01 diagonal
    Label centre = 0;           ///< label of the centre point (meaningful when split)
};

/// The tetrahedra of a cube: tets[0 .. count).
struct CubeTets {
    std::array<CubeTet, 12> tets{};
    std::size_t count = 0;
};

/// The tetrahedra of a cube under `plan`, in the order extract_interfaces() visits them: the 6 kuhn_tets, or
/// (plan.split) for each face in cube_faces order its two triangles on the chosen diagonal, each coned to
/// the centre (vertex 8, listed last).
CubeTets cube_tetrahedra(const CubePlan& plan);

/// Priorities per label (unlisted labels rank below every listed one).
class PriorityRule {
public:
    explicit PriorityRule(const std::map<Label, int>& priority);
    bool active() const { return active_; }
    /// The plan of the cube with these corner labels (indexed by corner bits).
    CubePlan plan(const std::array<Label, 8>& corners) const;

private:
    long long rank(Label label) const { return rank_[label]; }
    bool anti_diagonal(const std::array<Label, 8>& corners, const std::array<int, 4>& face) const;
    Label top_label(const std::array<Label, 8>& corners) const;
    static bool main_diagonal_crosses(const std::array<Label, 8>& corners, Label top);

    std::vector<long long> rank_;
    bool active_ = false;
};

} // namespace tissuemesh::surface::detail

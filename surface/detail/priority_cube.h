// The thin-tissue priority rule of extract_interfaces(): which diagonal each cube face uses and whether a
// cube is split into 12 tetrahedra around a centre point (see ExtractOptions::priority).
#pragma once

#include <array>
#include <map>
#include <vector>

#include "core/label_image.h"

namespace tissuemesh::surface::detail {

/// The 6 faces of a grid cube as corner cycles {c00, c10, c11, c01} (corner bits: 0 +x, 1 +y, 2 +z);
/// c00 is the face's lowest corner and c11 its highest, so c00-c11 is the Kuhn diagonal and c10-c01 the
/// other one.
constexpr std::array<std::array<int, 4>, 6> cube_faces{{
    {0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6},
}};

/// How one cube is tetrahedralized.
struct CubePlan {
    bool split = false;          ///< 12 tetrahedra around the cube centre instead of the 6 Kuhn ones
    std::array<bool, 6> anti{};  ///< face f (cube_faces order) uses its c10-c01 diagonal
    Label centre = 0;            ///< label of the centre point (meaningful when split)
};

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

#include "surface/detail/priority_cube.h"

#include <algorithm>
#include <limits>

namespace tissuemesh::surface::detail {

namespace {
constexpr long long unlisted = std::numeric_limits<long long>::min();
}

PriorityRule::PriorityRule(const std::map<Label, int>& priority)
    : rank_(std::size_t{1} << 16, unlisted), active_(!priority.empty())
{
    for (const auto& [label, value] : priority) rank_[label] = value;
}

/// A checkerboard face for a listed tissue T: T on the c10-c01 diagonal, the other two corners not T
/// and of lower rank. (The mirror case, T on c00-c11, is the Kuhn diagonal already.)
bool PriorityRule::anti_diagonal(const std::array<Label, 8>& corners, const std::array<int, 4>& face) const
{
    const Label a = corners[face[0]], b = corners[face[1]], c = corners[face[2]], d = corners[face[3]];
    return b == d && rank(b) != unlisted && rank(a) < rank(b) && rank(c) < rank(b);
}

/// Highest rank; ties: the most frequent; then the smallest label.
Label PriorityRule::top_label(const std::array<Label, 8>& corners) const
{
    Label best = corners[0];
    int best_count = 0;
    for (const Label label : corners) {
        int count = 0;
        for (const Label other : corners) count += other == label;
        const bool better = rank(label) != rank(best) ? rank(label) > rank(best)
                                                      : (count != best_count ? count > best_count : label < best);
        if (best_count == 0 || better) best = label, best_count = count;
    }
    return best;
}

/// The Kuhn main diagonal 0-7 would cross T: corners 0 and 7 are not T and every path of cube edges
/// between them passes through a T corner (a one-voxel layer of T between them).
bool PriorityRule::main_diagonal_crosses(const std::array<Label, 8>& corners, Label top)
{
    if (corners[0] == top || corners[7] == top) return false;
    int reached = 1;
    for (int round = 0; round < 3; ++round)
        for (int c = 0; c < 8; ++c)
            for (int bit = 1; bit < 8; bit <<= 1)
                if ((reached >> c & 1) && corners[c ^ bit] != top) reached |= 1 << (c ^ bit);
    return !(reached >> 7 & 1);
}

CubeTets cube_tetrahedra(const CubePlan& plan)
{
    CubeTets out;
    if (!plan.split) {
        std::copy(kuhn_tets.begin(), kuhn_tets.end(), out.tets.begin());
        out.count = kuhn_tets.size();
        return out;
    }
    for (std::size_t f = 0; f < cube_faces.size(); ++f) {
        const auto& c = cube_faces[f];
        if (plan.anti[f]) {
            out.tets[out.count++] = {c[1], c[3], c[0], 8};
            out.tets[out.count++] = {c[1], c[3], c[2], 8};
        } else {
            out.tets[out.count++] = {c[0], c[2], c[1], 8};
            out.tets[out.count++] = {c[0], c[2], c[3], 8};
        }
    }
    return out;
}

CubePlan PriorityRule::plan(const std::array<Label, 8>& corners) const
{
    CubePlan plan;
    if (!active_) return plan;
    bool any_anti = false;
    for (std::size_t f = 0; f < cube_faces.size(); ++f) {
        plan.anti[f] = anti_diagonal(corners, cube_faces[f]);
        any_anti = any_anti || plan.anti[f];
    }
    plan.centre = top_label(corners);
    if (rank(plan.centre) == unlisted) return plan; // no listed tissue: no face can be anti either
    // Split when the top tissue's corners are not already joined by the cube's Kuhn edges (pairs of
    // corners one of which is a subset of the other), or when a face needs its other diagonal.
    int reached = 0, first = -1;
    for (int c = 0; c < 8; ++c)
        if (corners[c] == plan.centre && first < 0) first = c;
    reached = 1 << first;
    for (bool grew = true; grew;) {
        grew = false;
        for (int x = 0; x < 8; ++x)
            for (int y = 0; y < 8; ++y)
                if ((reached >> x & 1) && !(reached >> y & 1) && corners[y] == plan.centre &&
                    ((x & y) == x || (x & y) == y))
                    reached |= 1 << y, grew = true;
    }
    int all = 0;
    for (int c = 0; c < 8; ++c)
        if (corners[c] == plan.centre) all |= 1 << c;
    plan.split = any_anti || reached != all || main_diagonal_crosses(corners, plan.centre);
    return plan;
}

} // namespace tissuemesh::surface::detail

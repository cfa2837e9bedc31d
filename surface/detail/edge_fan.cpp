#include "surface/detail/edge_fan.h"

#include <algorithm>
#include <vector>

#include "surface/detail/cgal_intersections.h"

namespace tissuemesh::surface::detail {
namespace {

/// The tissue a right-hand turn about the edge meets first after the blade, and the one it leaves behind.
Label ahead(const FanBlade& blade) { return blade.forward ? blade.side.to : blade.side.from; }
Label behind(const FanBlade& blade) { return blade.forward ? blade.side.from : blade.side.to; }

} // namespace

FanOrder fan_order(const Vec3& a, const Vec3& b, std::span<const FanBlade> blades)
{
    const std::size_t n = blades.size();
    if (n < 2) return FanOrder::in_order;
    // Angles of a right-hand turn about b - a, from blade 0: half 0 holds [0, pi), half 1 [pi, 2 pi).
    // orientation(a, b, p, q) is the sign of the sine of the turn from p to q.
    const Vec3& first = blades[0].apex;
    const Vec3 axis = b - a;
    thread_local std::vector<std::pair<int, std::uint32_t>> turn;  // (half, blade); scratch: edits ask often
    turn.assign(1, {0, 0});
    for (std::uint32_t i = 1; i < n; ++i) {
        const int sine = orientation(a, b, first, blades[i].apex);
        if (sine != 0) {
            turn.emplace_back(sine > 0 ? 0 : 1, i);
            continue;
        }
        // In the plane of blade 0: on its side of the edge (overlapping it) or opposite (at pi). The sign of
        // the dot product of the two apexes' offsets across the axis, times |axis|^2; zero for a flat blade.
        const Vec3 u = first - a, w = blades[i].apex - a;
        const double across = dot(u, w) * dot(axis, axis) - dot(u, axis) * dot(w, axis);
        if (!(across < 0)) return FanOrder::overlapping;
        turn.emplace_back(1, i);
    }
    const auto earlier = [&](const std::pair<int, std::uint32_t>& p, const std::pair<int, std::uint32_t>& q) {
        if (p.first != q.first) return p.first < q.first;
        return p.second != q.second && orientation(a, b, blades[p.second].apex, blades[q.second].apex) > 0;
    };
    std::sort(turn.begin() + 1, turn.end(), earlier);
    for (std::size_t i = 0; i < n; ++i) {
        const auto& p = turn[i];
        const auto& q = turn[(i + 1) % n];
        // Equal angles within one half (never across halves: blade 0 alone is at 0) overlap.
        if (i + 1 < n && p.first == q.first && !earlier(p, q)) return FanOrder::overlapping;
        if (ahead(blades[p.second]) != behind(blades[q.second])) return FanOrder::out_of_order;
    }
    return FanOrder::in_order;
}

} // namespace tissuemesh::surface::detail

#include "surface/detail/edge_fan.h"

#include <algorithm>
#include <array>
#include <cmath>
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
    thread_local std::vector<std::pair<int, std::uint32_t>> turn; // (half, blade); scratch: edits ask often
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

double smallest_sector_deg(const Vec3& a, const Vec3& b, std::span<const FanBlade> blades)
{
    constexpr double pi = 3.14159265358979323846;
    const std::size_t n = blades.size();
    const double length = norm(b - a);
    if (n < 2 || n > 16 || !(length > 0)) return 360;
    // Angles of a right-hand turn about b - a in a frame (u, v) across the edge.
    const Vec3 e = (1 / length) * (b - a);
    const Vec3 across = cross(e, std::abs(e[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0});
    const Vec3 u = (1 / norm(across)) * across, v = cross(e, u);
    std::array<double, 16> turn{};
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3 r = blades[i].apex - a;
        turn[i] = std::atan2(dot(r, v), dot(r, u));
    }
    std::sort(turn.begin(), turn.begin() + static_cast<std::ptrdiff_t>(n));
    double smallest = 360;
    for (std::size_t i = 0; i < n; ++i) {
        const double next = i + 1 < n ? turn[i + 1] : turn[0] + 2 * pi;
        smallest = std::min(smallest, (next - turn[i]) * 180 / pi);
    }
    return smallest;
}

double smallest_sector_deg(const InterfaceComplex& complex)
{
    // Every (edge, triangle) once, sorted by edge: the triangles of an edge are neighbours in the list.
    struct Use {
        std::uint32_t a, b, triangle;
    };
    std::vector<Use> uses;
    uses.reserve(3 * complex.triangles.size());
    for (std::uint32_t t = 0; t < complex.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t p = complex.triangles[t][k], q = complex.triangles[t][(k + 1) % 3];
            uses.push_back({std::min(p, q), std::max(p, q), t});
        }
    std::sort(uses.begin(), uses.end(), [](const Use& x, const Use& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
    double smallest = 360;
    std::vector<FanBlade> blades;
    for (std::size_t i = 0; i < uses.size();) {
        std::size_t j = i;
        blades.clear();
        for (; j < uses.size() && uses[j].a == uses[i].a && uses[j].b == uses[i].b; ++j)
            blades.push_back(blade_on(complex.triangles[uses[j].triangle], uses[i].a, uses[i].b, complex.vertices,
                                      complex.sides[uses[j].triangle]));
        smallest =
            std::min(smallest, smallest_sector_deg(complex.vertices[uses[i].a], complex.vertices[uses[i].b], blades));
        i = j;
    }
    return smallest;
}

} // namespace tissuemesh::surface::detail

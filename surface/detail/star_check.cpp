#include "surface/detail/star_check.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "surface/detail/cgal_intersections.h"
#include "surface/detail/plane_side.h"

namespace tissuemesh::surface::detail {
namespace {

constexpr std::size_t max_sheets = 8;

/// Triangle t seen from its corner v: the next two corners in its vertex order.
std::pair<std::uint32_t, std::uint32_t> opposite(const Triangle& t, std::uint32_t v)
{
    const int k = t[0] == v ? 0 : t[1] == v ? 1 : 2;
    return {t[(k + 1) % 3], t[(k + 2) % 3]};
}

void pairwise(std::span<const std::uint32_t> first, std::span<const std::uint32_t> second, bool same,
              const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles,
              std::vector<std::uint32_t>& offenders)
{
    for (std::size_t i = 0; i < first.size(); ++i)
        for (std::size_t j = same ? i + 1 : 0; j < second.size(); ++j)
            if (triangles_meet(positions, triangles[first[i]], triangles[second[j]])) {
                offenders.push_back(first[i]);
                offenders.push_back(second[j]);
            }
}

/// Whether the fan `sheet` around v certainly projects one-to-one along its mean normal (see star_check.h).
bool fan_is_embedded(std::uint32_t v, std::span<const std::uint32_t> sheet, bool closed,
                     const std::vector<Vec3>& positions, const std::vector<Triangle>& triangles)
{
    const Vec3& o = positions[v];
    Vec3 n{0, 0, 0};
    for (const std::uint32_t t : sheet) {
        const auto [a, b] = opposite(triangles[t], v);
        n = n + cross(positions[a] - o, positions[b] - o);
    }
    const double length = norm(n);
    if (!(length > 0)) return false;
    n = (1 / length) * n;
    // Every triangle must face n (its projection across n then turns counterclockwise by less than a half
    // turn), and the turns must add up to one full turn (closed fan) or less (open fan): counted as the
    // times the projected link passes the direction of its first vertex, without angles.
    const auto project = [&](std::uint32_t w) {
        const Vec3 p = positions[w] - o;
        return p - dot(p, n) * n;
    };
    const std::uint32_t first = opposite(triangles[sheet[0]], v).first;
    const Vec3 reference = project(first);
    bool unsure = false;
    // 0: the first half turn from the reference, [0, pi); 1: the second, [pi, 2 pi). The reference vertex
    // itself is at 0 (a closed fan's last step lands on it); any other vertex almost in its direction leaves
    // the count unsure. Near pi a wrong half cannot change the count: every step turns by less than pi, so
    // no step leaves the neighbourhood of pi into the first half.
    const auto half = [&](std::uint32_t w) {
        if (w == first) return 0;
        const Vec3 q = project(w);
        const double sine = dot(cross(reference, q), n);
        if (std::abs(sine) <= 1e-9 * norm(reference) * norm(q)) {
            if (dot(reference, q) > 0) unsure = true;
            return 1;
        }
        return sine > 0 ? 0 : 1;
    };
    int wraps = 0;
    for (const std::uint32_t t : sheet) {
        const auto [a, b] = opposite(triangles[t], v);
        const Vec3 normal = cross(positions[a] - o, positions[b] - o);
        if (!(dot(normal, n) > 1e-9 * norm(normal))) return false;
        // A step from the second half into the first passes the reference direction.
        if (half(a) == 1 && half(b) == 0) ++wraps;
    }
    if (unsure) return false;
    return closed ? wraps == 1 : wraps == 0;
}

} // namespace

bool triangles_meet(const std::vector<Vec3>& p, const Triangle& a, const Triangle& b)
{
    // Boxes first: apart unless they overlap on every axis (pairs with a common vertex always overlap).
    for (int axis = 0; axis < 3; ++axis) {
        const double a_low = std::min({p[a[0]][axis], p[a[1]][axis], p[a[2]][axis]});
        const double a_high = std::max({p[a[0]][axis], p[a[1]][axis], p[a[2]][axis]});
        const double b_low = std::min({p[b[0]][axis], p[b[1]][axis], p[b[2]][axis]});
        const double b_high = std::max({p[b[0]][axis], p[b[1]][axis], p[b[2]][axis]});
        if (a_high < b_low || b_high < a_low) return false;
    }
    if (certainly_apart(a, {p[a[0]], p[a[1]], p[a[2]]}, b, {p[b[0]], p[b[1]], p[b[2]]})) return false;
    return triangles_intersect(p, a, b);
}

bool order_sheets(std::uint32_t v, std::span<const std::uint32_t> star, const std::vector<Triangle>& triangles,
                  std::vector<std::uint32_t>& order, std::vector<std::uint32_t>& starts, std::uint32_t& closed_bits)
{
    order.clear();
    starts.clear();
    closed_bits = 0;
    const std::size_t k = star.size();
    if (k > 64) return false;
    // Per triangle its corners after v (a, b), and the triangle that follows it around v: the other one on
    // edge vb, which must have b as its a; none on a junction edge (three or more triangles on vb).
    std::array<std::uint32_t, 64> a{}, b{};
    std::array<std::int8_t, 64> next{}, previous{};
    for (std::size_t i = 0; i < k; ++i) std::tie(a[i], b[i]) = opposite(triangles[star[i]], v);
    for (std::size_t i = 0; i < k; ++i) next[i] = previous[i] = -1;
    for (std::size_t i = 0; i < k; ++i) {
        int uses = 0, follower = -1;
        for (std::size_t j = 0; j < k; ++j) {
            uses += (a[j] == b[i]) + (b[j] == b[i]);
            if (j != i && a[j] == b[i]) follower = static_cast<int>(j);
        }
        if (uses != 2) continue;        // a junction edge (or an open one): the fan ends here
        if (follower < 0) return false; // the other triangle on vb runs the same way: not a fan
        next[i] = static_cast<std::int8_t>(follower);
        previous[follower] = static_cast<std::int8_t>(i);
    }
    std::uint64_t used = 0;
    for (std::size_t s = 0; s < k; ++s) {
        if (used >> s & 1) continue;
        std::size_t begin = s; // back up to the start of the fan (or all the way round)
        for (std::size_t steps = 0; steps < k && previous[begin] >= 0 && static_cast<std::size_t>(previous[begin]) != s;
             ++steps)
            begin = static_cast<std::size_t>(previous[begin]);
        if (starts.size() >= 32) return false;
        starts.push_back(static_cast<std::uint32_t>(order.size()));
        for (std::size_t at = begin;;) {
            if (used >> at & 1) {
                if (at != begin) return false;
                closed_bits |= std::uint32_t{1} << (starts.size() - 1);
                break;
            }
            used |= std::uint64_t{1} << at;
            order.push_back(star[at]);
            if (next[at] < 0) break;
            at = static_cast<std::size_t>(next[at]);
        }
    }
    return true;
}

StarSheets build_star_sheets(const std::vector<Triangle>& triangles, const Rows& stars)
{
    // Each vertex's ordered star takes the place of its star; its sheet starts go to a list per block of
    // vertices, joined in order afterwards, so the result does not depend on the threads.
    const std::size_t vertex_count = stars.size();
    StarSheets out;
    out.stars.offsets = stars.offsets;
    out.stars.items.resize(stars.items.size());
    out.closed_bits.assign(vertex_count, 0);
    out.irregular.assign(vertex_count, 0);
    std::vector<std::uint32_t> sheet_count(vertex_count, 0);
    constexpr std::size_t block = 16384;
    const std::size_t blocks = (vertex_count + block - 1) / block;
    std::vector<std::vector<std::uint32_t>> block_starts(blocks);
#pragma omp parallel
    {
        std::vector<std::uint32_t> order, starts;
#pragma omp for schedule(dynamic, 1)
        for (std::size_t b = 0; b < blocks; ++b) {
            std::vector<std::uint32_t>& all_starts = block_starts[b];
            for (std::size_t v = b * block; v < std::min(vertex_count, (b + 1) * block); ++v) {
                std::uint32_t closed = 0;
                const bool regular =
                    order_sheets(static_cast<std::uint32_t>(v), stars[v], triangles, order, starts, closed) &&
                    starts.size() <= max_sheets;
                if (!regular) {
                    // Keep the star whole and unordered: every pair is tested.
                    out.irregular[v] = 1;
                    order.assign(stars[v].begin(), stars[v].end());
                    starts.assign(1, 0);
                    closed = 0;
                }
                std::copy(order.begin(), order.end(), out.stars.items.begin() + stars.offsets[v]);
                all_starts.insert(all_starts.end(), starts.begin(), starts.end());
                sheet_count[v] = static_cast<std::uint32_t>(starts.size());
                out.closed_bits[v] = static_cast<std::uint8_t>(closed);
            }
        }
    }
    out.sheets = join_rows(sheet_count, block_starts);
    return out;
}

bool star_is_clean(std::uint32_t v, std::span<const std::uint32_t> star, const std::vector<Vec3>& positions,
                   const std::vector<Triangle>& triangles, std::span<const std::uint32_t> changed)
{
    thread_local std::vector<std::uint32_t> order, starts, offenders, fresh, rest;
    std::uint32_t closed = 0;
    offenders.clear();
    const auto is_changed = [&](std::uint32_t t) {
        return changed.empty() || std::find(changed.begin(), changed.end(), t) != changed.end();
    };
    // Only pairs with a changed triangle can have started to meet.
    const auto changed_pairs = [&](std::span<const std::uint32_t> x, std::span<const std::uint32_t> y, bool same) {
        if (changed.empty()) return pairwise(x, y, same, positions, triangles, offenders);
        fresh.clear();
        rest.clear();
        for (const std::uint32_t t : x) (is_changed(t) ? fresh : rest).push_back(t);
        if (same) {
            pairwise(fresh, fresh, true, positions, triangles, offenders);
            pairwise(fresh, rest, false, positions, triangles, offenders);
            return;
        }
        pairwise(fresh, y, false, positions, triangles, offenders);
        rest.clear();
        for (const std::uint32_t t : y)
            if (is_changed(t)) rest.push_back(t);
        fresh.clear();
        for (const std::uint32_t t : x)
            if (!is_changed(t)) fresh.push_back(t);
        pairwise(fresh, rest, false, positions, triangles, offenders);
    };
    if (!order_sheets(v, star, triangles, order, starts, closed)) {
        changed_pairs(star, star, true);
        return offenders.empty();
    }
    const std::span<const std::uint32_t> all(order);
    const auto sheet = [&](std::size_t s) {
        const std::size_t end = s + 1 < starts.size() ? starts[s + 1] : order.size();
        return all.subspan(starts[s], end - starts[s]);
    };
    const auto touched = [&](std::span<const std::uint32_t> x) { return std::any_of(x.begin(), x.end(), is_changed); };
    for (std::size_t s = 0; s < starts.size(); ++s) {
        const bool touched_s = touched(sheet(s));
        if (touched_s && !fan_is_embedded(v, sheet(s), closed >> s & 1, positions, triangles)) {
            changed_pairs(sheet(s), sheet(s), true);
            if (!offenders.empty()) return false;
        }
        for (std::size_t r = s + 1; r < starts.size(); ++r) {
            if (!touched_s && !touched(sheet(r))) continue;
            changed_pairs(sheet(s), sheet(r), false);
            if (!offenders.empty()) return false;
        }
    }
    return true;
}

void star_offenders(std::uint32_t v, const StarSheets& sheets, const std::vector<Vec3>& positions,
                    const std::vector<Triangle>& triangles, std::vector<std::uint32_t>& offenders)
{
    const auto star = sheets.stars[v];
    if (sheets.irregular[v]) return pairwise(star, star, true, positions, triangles, offenders);
    const auto starts = sheets.sheets[v];
    const std::size_t count = starts.size();
    const auto sheet = [&](std::size_t s) {
        const std::size_t end = s + 1 < count ? starts[s + 1] : star.size();
        return star.subspan(starts[s], end - starts[s]);
    };
    for (std::size_t s = 0; s < count; ++s) {
        const bool closed = s < max_sheets && (sheets.closed_bits[v] >> s & 1);
        if (!fan_is_embedded(v, sheet(s), closed, positions, triangles))
            pairwise(sheet(s), sheet(s), true, positions, triangles, offenders);
        for (std::size_t r = s + 1; r < count; ++r)
            pairwise(sheet(s), sheet(r), false, positions, triangles, offenders);
    }
}

} // namespace tissuemesh::surface::detail

// ComplexEditor::move_together(): many vertex moves checked at once. Checking each move on its own
// (try_move) costs a grid query and a transaction per vertex; smoothing moves every vertex of the
// complex per step, so here all moves are made first and each changed triangle is judged once, in
// parallel, against its neighbours in the grid. Only the offenders are put back and judged again.
#include <algorithm>

#include "core/error.h"
#include "surface/detail/cgal_intersections.h"
#include "surface/detail/complex_editor.h"
#include "surface/detail/edit_rules.h"
#include "surface/detail/mesh_measures.h"
#include "surface/detail/plane_side.h"

namespace tissuemesh::surface::detail {
namespace {

/// From intersection_rule on, a rule involves other triangles (partners), whose moves go back too.
enum Rule : std::uint8_t { none = 0, shape_rule, normal_rule, intersection_rule, gap_rule, wedge_rule, fan_rule };

TriangleCorners corners_at(const std::vector<Vec3>& positions, const Triangle& t)
{
    return {positions[t[0]], positions[t[1]], positions[t[2]]};
}

} // namespace

std::uint8_t ComplexEditor::judge_moved(std::uint32_t t, const std::vector<Vec3>& start,
                                        const std::vector<char>& judged, const BoxIndex& index,
                                        std::vector<std::uint32_t>* partners) const
{
    const Triangle& tri = triangles_[t];
    const TriangleCorners now = corners(t), before = corners_at(start, tri);
    switch (single_triangle_rule(now, before, min_angle_, max_tilt_)) {
    case TriangleRule::shape: return shape_rule;
    case TriangleRule::tilt: return normal_rule;
    case TriangleRule::none: break;
    }
    // Around a junction edge every triangle of the fan is a partner: all their moves go back together,
    // which restores the order the fan had (edge_fan.h).
    thread_local std::vector<std::uint32_t> fan;
    for (int k = 0; k < 3; ++k) {
        const std::uint32_t p = tri[k], q = tri[(k + 1) % 3];
        if (!may_be_junction_edge(p, q)) continue;
        fan.clear();
        if (fan_around(p, q, nullptr, nullptr, &fan) == FanOrder::in_order) continue;
        if (partners) partners->insert(partners->end(), fan.begin(), fan.end());
        return fan_rule;
    }
    const double gap = limits_.min_gap_mm;
    const Box3 box = bounding_box(now, gap), tight = bounding_box(now);
    // Every triangle whose box meets `box`, in the index's order (deterministic; which rule is found
    // first only feeds the counters).
    std::uint8_t found = none;
    index.visit(box, [&](std::uint32_t u) {
        if (u == t || (judged[u] && u < t)) return false;
        const std::uint8_t broken = pair_rule(t, u, now, before, tight, start);
        if (broken == none) return false;
        if (found == none) found = broken;
        if (partners) partners->push_back(u);
        return partners == nullptr;
    });
    return found;
}

std::uint8_t ComplexEditor::pair_rule(std::uint32_t t, std::uint32_t u, const TriangleCorners& now,
                                      const TriangleCorners& before, const Box3& tight,
                                      const std::vector<Vec3>& start) const
{
    const Triangle& a = triangles_[t];
    const Triangle& b = triangles_[u];
    const TriangleCorners other = corners(u);
    if (shares_vertex(a, b)) {
        // No gap between neighbours, but a wedge at a single shared vertex; most are passed by the plane
        // test before the exact one.
        if (!certainly_apart(a, now, b, other) && triangles_intersect(positions_, a, b)) return intersection_rule;
        if (closes_wedge(a, now, &before, b, other, corners_at(start, b), limits_.min_wedge_deg)) return wedge_rule;
        return none;
    }
    if (boxes_overlap(tight, bounding_box(other)) && !certainly_apart(a, now, b, other) &&
        triangles_intersect(positions_, a, b))
        return intersection_rule;
    const double gap = limits_.min_gap_mm;
    if (gap > 0 && !(sides_[t] == sides_[u]) && !farther_than(now, other, gap) &&
        closes_gap(now, before, other, corners_at(start, b), gap))
        return gap_rule;
    return none;
}

/// Every alive triangle is filed in batch_index_ under a box holding its current box (the invariant that
/// lets a batch reuse the index: apply() drops it). A batch whose changed triangles' boxes (now in boxes_)
/// all fit in the boxes they are filed under reuses it: a box larger than needed only brings candidates
/// that are further apart than the gap, which no rule refuses (smoothing's halved steps stay within the
/// boxes of the full ones). Otherwise the index is built again.
void ComplexEditor::refresh_batch_index(const std::vector<std::uint32_t>& changed)
{
    const auto holds = [](const CompactBox& outer, const CompactBox& inner) {
        for (int i = 0; i < 3; ++i)
            if (inner.low[i] < outer.low[i] || outer.high[i] < inner.high[i]) return false;
        return true;
    };
    if (batch_index_valid_ && std::all_of(changed.begin(), changed.end(),
                                          [&](std::uint32_t t) { return holds(batch_index_.filed_box(t), boxes_[t]); }))
        return;
    std::vector<std::uint32_t> alive;
    for (std::uint32_t t = 0; t < triangles_.size(); ++t)
        if (alive_[t]) alive.push_back(t);
    batch_index_ = BoxIndex(boxes_, alive);
    batch_index_valid_ = true;
}

std::vector<char> ComplexEditor::move_together(const std::vector<std::uint32_t>& vertices,
                                               const std::vector<Vec3>& targets)
{
    if (limits_.tolerate_existing_intersections)
        throw AlgorithmError("move_together: not available in tolerant mode (use try_move)");
    const std::vector<Vec3> start = positions_;
    std::vector<char> moved(positions_.size(), 0), judged(triangles_.size(), 0);
    std::vector<std::uint32_t> round; // triangles to judge, ascending
    std::vector<char> listed(triangles_.size(), 0);
    // The triangles of the stars of `from` into `round`, ascending, each once (marks instead of a sort:
    // a batch lists the stars of millions of vertices).
    const auto stars_of = [&](const std::vector<std::uint32_t>& from) {
        round.clear();
        std::size_t count = 0;
        for (const std::uint32_t v : from)
            for (const std::uint32_t t : stars_[v])
                if (!listed[t]) listed[t] = 1, ++count;
        if (count > triangles_.size() / 64) {
            for (std::uint32_t t = 0; t < triangles_.size(); ++t)
                if (listed[t]) round.push_back(t), listed[t] = 0;
            return;
        }
        for (const std::uint32_t v : from)
            for (const std::uint32_t t : stars_[v])
                if (listed[t]) round.push_back(t), listed[t] = 0;
        std::sort(round.begin(), round.end());
    };
    std::vector<std::uint32_t> movers;
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        if (!vertex_alive(vertices[i])) continue;
        positions_[vertices[i]] = targets[i];
        moved[vertices[i]] = 1;
        movers.push_back(vertices[i]);
    }
    stars_of(movers);
    // While judged, a changed triangle is filed under the box of both its old and its new place, so that
    // a query finds it wherever its vertices are (each is either back at the start or at its target).
    // Batches have their own index; the editor's grid is rebuilt when a single edit next needs it.
    const std::vector<std::uint32_t> changed = round;
    for (const std::uint32_t t : changed)
        boxes_[t] = compact(box_union(bounding_box(corners_at(start, triangles_[t])), bounding_box(corners(t))));
    grid_ = TriangleGrid();
    grid_ready_ = false;
    refresh_batch_index(changed);
    const BoxIndex& index = batch_index_;
    std::vector<std::uint8_t> verdict;
    while (!round.empty()) {
        verdict.assign(round.size(), none);
        for (const std::uint32_t t : round) judged[t] = 1;
        const auto count = static_cast<std::int64_t>(round.size());
        // Later rounds judge a few triangles: waking the other threads would cost more than it saves.
#pragma omp parallel for schedule(dynamic, 512) if (count > 4096)
        for (std::int64_t i = 0; i < count; ++i)
            verdict[static_cast<std::size_t>(i)] =
                judge_moved(round[static_cast<std::size_t>(i)], start, judged, index, nullptr);
        // Sequential, in index order: which vertices go back does not depend on the threads.
        std::vector<std::uint32_t> back, partners;
        for (std::size_t i = 0; i < round.size(); ++i) {
            if (verdict[i] == none) continue;
            const std::uint32_t t = round[i];
            partners.assign(1, t);
            if (verdict[i] >= intersection_rule) judge_moved(t, start, judged, index, &partners);
            ++(verdict[i] == shape_rule          ? counters_.shape
               : verdict[i] == normal_rule       ? counters_.normal
               : verdict[i] == intersection_rule ? counters_.intersection
               : verdict[i] == gap_rule          ? counters_.gap
                                                 : counters_.wedge);
            for (const std::uint32_t p : partners)
                for (const std::uint32_t v : triangles_[p])
                    if (moved[v]) moved[v] = 0, positions_[v] = start[v], back.push_back(v);
        }
        for (const std::uint32_t t : round) judged[t] = 0;
        stars_of(back);
    }
    for (const std::uint32_t t : changed) boxes_[t] = compact(bounding_box(corners(t)));
    std::vector<char> result(vertices.size(), 0);
    for (std::size_t i = 0; i < vertices.size(); ++i) result[i] = moved[vertices[i]];
    counters_.accepted += static_cast<std::size_t>(std::count(result.begin(), result.end(), 1));
    return result;
}

} // namespace tissuemesh::surface::detail

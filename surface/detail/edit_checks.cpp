// ComplexEditor's geometric checks of an edit before it is applied: shape and tilt of the changed triangles,
// then intersections, wedges and gaps against the other triangles near them (the edits are in
// complex_editor.cpp, the batch judgements in move_together.cpp).
#include <algorithm>

#include "surface/detail/cgal_intersections.h"
#include "surface/detail/complex_editor.h"
#include "surface/detail/edit_rules.h"
#include "surface/detail/mesh_measures.h"
#include "surface/detail/plane_side.h"

namespace tissuemesh::surface::detail {

bool ComplexEditor::shape_ok(const Change& change)
{
    const Triangle& t = change.triangle;
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] ||
        are_collinear(positions_[t[0]], positions_[t[1]], positions_[t[2]])) {
        ++counters_.shape;
        return false;
    }
    const TriangleCorners now{positions_[t[0]], positions_[t[1]], positions_[t[2]]};
    if (has_angle_below(now, min_angle_) && smallest_angle_deg(now) < smallest_angle_deg(change.before) - 1e-9) {
        ++counters_.shape;
        return false;
    }
    if (tilts_beyond(normal_of(now), normal_of(change.before), max_tilt_)) {
        ++counters_.normal;
        return false;
    }
    return true;
}

/// No changed triangle meets another (changed or not) improperly, nor comes closer than the gap to one
/// it shares no vertex with (unless its old version was closer still).
bool ComplexEditor::meet(const Triangle& a, const TriangleCorners& pa, const Triangle& b,
                         const TriangleCorners& pb) const
{
    if (certainly_apart(a, pa, b, pb)) return false;
    return triangles_intersect(positions_, a, b);
}

bool ComplexEditor::clear_of_others(const std::vector<Change>& changes, const std::vector<std::uint32_t>& excluded)
{
    const double gap = limits_.min_gap_mm;
    std::vector<TriangleCorners>& shapes = clear_shapes_;
    std::vector<Box3>& boxes = clear_boxes_;
    shapes.clear();
    boxes.clear();
    Box3 all{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
    for (const Change& change : changes) {
        const Triangle& a = change.triangle;
        shapes.push_back({positions_[a[0]], positions_[a[1]], positions_[a[2]]});
        boxes.push_back(bounding_box(shapes.back(), gap));
        for (int i = 0; i < 3; ++i) {
            all.low[i] = std::min(all.low[i], boxes.back().low[i]);
            all.high[i] = std::max(all.high[i], boxes.back().high[i]);
        }
    }
    // Outside repair the budget is 0: the first intersection refuses the edit.
    std::size_t meetings = 0;
    const auto meets = [&] {
        if (++meetings <= intersection_budget_) return false;
        ++counters_.intersection;
        return true;
    };
    // A change that only moves vertices has its old self to compare with; new triangles do not.
    std::vector<const TriangleCorners*>& before = clear_before_;
    before.assign(changes.size(), nullptr);
    for (std::size_t i = 0; i < changes.size(); ++i)
        if (changes[i].slot < triangles_.size() && alive_[changes[i].slot] &&
            same_vertex_set(changes[i].triangle, triangles_[changes[i].slot]))
            before[i] = &changes[i].before;
    for (std::size_t i = 0; i < changes.size(); ++i)
        for (std::size_t j = i + 1; j < changes.size(); ++j) {
            if ((same_vertex_set(changes[i].triangle, changes[j].triangle) ||
                 (boxes_overlap(boxes[i], boxes[j]) &&
                  meet(changes[i].triangle, shapes[i], changes[j].triangle, shapes[j]))) &&
                meets())
                return false;
            if (closes_wedge(changes[i].triangle, shapes[i], before[j] ? before[i] : nullptr, changes[j].triangle,
                             shapes[j], changes[j].before, limits_.min_wedge_deg)) {
                ++counters_.wedge;
                return false;
            }
        }
    grid_.query(all, nearby_);
    for (const std::uint32_t t : nearby_) {
        // The box first: most candidates end there, and the grid holds only alive triangles anyway (one cache
        // miss fewer per candidate).
        if (!boxes_overlap(all, boxes_[t]) || !alive_[t] ||
            std::find(excluded.begin(), excluded.end(), t) != excluded.end())
            continue;
        const TriangleCorners cb = corners(t);
        const Box3 box = bounding_box(cb);
        if (!boxes_overlap(all, box)) continue;
        for (std::size_t i = 0; i < changes.size(); ++i) {
            if (!boxes_overlap(boxes[i], box)) continue;
            const Triangle& a = changes[i].triangle;
            if ((same_vertex_set(a, triangles_[t]) || meet(a, shapes[i], triangles_[t], cb)) && meets()) return false;
            if (shares_vertex(a, triangles_[t]) &&
                closes_wedge(a, shapes[i], before[i], triangles_[t], cb, cb, limits_.min_wedge_deg)) {
                ++counters_.wedge;
                return false;
            }
            // The gap keeps layers apart: it applies between different patches only (within a patch, folds
            // are what the normal and intersection tests are for), and is measured between vertices and
            // faces (the closest approach of nearly parallel layers).
            if (gap > 0 && !shares_vertex(a, triangles_[t]) && !farther_than(shapes[i], cb, gap) &&
                !(sides_[t] == side_of(changes[i])) && closes_gap(shapes[i], changes[i].before, cb, cb, gap)) {
                ++counters_.gap;
                return false;
            }
        }
    }
    return true;
}

std::size_t ComplexEditor::intersections_involving(const std::vector<std::uint32_t>& slots)
{
    std::size_t count = 0;
    std::vector<std::uint32_t> sorted = slots;
    std::sort(sorted.begin(), sorted.end());
    for (const std::uint32_t s : slots) {
        const Box3 box = bounding_box(corners(s));
        grid_.query(box, nearby_);
        for (const std::uint32_t t : nearby_) {
            if (!alive_[t] || t == s) continue;
            const bool among = std::binary_search(sorted.begin(), sorted.end(), t);
            if ((among && t < s) || !boxes_overlap(box, bounding_box(corners(t)))) continue;
            if (same_vertex_set(triangles_[s], triangles_[t]) ||
                triangles_intersect(positions_, triangles_[s], triangles_[t]))
                ++count;
        }
    }
    return count;
}

void ComplexEditor::set_budget(const std::vector<std::uint32_t>& slots)
{
    intersection_budget_ = limits_.tolerate_existing_intersections ? intersections_involving(slots) : 0;
}

LabelPair ComplexEditor::side_of(const Change& change) const
{
    return change.slot < sides_.size() ? sides_[change.slot] : change.side;
}

FanOrder ComplexEditor::fan_around(std::uint32_t p, std::uint32_t q, const std::vector<Change>* changes,
                                   const std::vector<std::uint32_t>* excluded,
                                   std::vector<std::uint32_t>* members) const
{
    thread_local std::vector<FanBlade> blades; // scratch: asked for every junction edge an edit touches
    blades.clear();
    for (const std::uint32_t t : stars_[p]) {
        if (!contains(triangles_[t], q) ||
            (excluded && std::find(excluded->begin(), excluded->end(), t) != excluded->end()))
            continue;
        blades.push_back(blade_on(triangles_[t], p, q, positions_, sides_[t]));
        if (members) members->push_back(t);
    }
    if (changes)
        for (const Change& change : *changes)
            if (contains(change.triangle, p) && contains(change.triangle, q))
                blades.push_back(blade_on(change.triangle, p, q, positions_, side_of(change)));
    return blades.size() < 3 ? FanOrder::in_order : fan_order(positions_[p], positions_[q], blades);
}

bool ComplexEditor::fans_in_order(const std::vector<Change>& changes, const std::vector<std::uint32_t>& excluded)
{
    // Repair untangles crossings, which tangle the junctions they pass; its moves may go through tangled
    // states on the way (measured: with a budget of "no more than before" per edit, a bulge through the thin
    // phantom's shell was left crossing), and its final check_complex() refuses any tangle left.
    if (limits_.tolerate_existing_intersections) return true;
    std::vector<std::pair<std::uint32_t, std::uint32_t>>& edges = fan_edges_;
    edges.clear();
    for (const Change& change : changes)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t p = change.triangle[k], q = change.triangle[(k + 1) % 3];
            if (may_be_junction_edge(p, q)) edges.emplace_back(std::min(p, q), std::max(p, q));
        }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (const auto& [p, q] : edges)
        if (fan_around(p, q, &changes, &excluded, nullptr) != FanOrder::in_order) {
            ++counters_.wedge;
            return false;
        }
    return true;
}

bool ComplexEditor::acceptable(const std::vector<Change>& changes, const std::vector<std::uint32_t>& removed)
{
    for (const Change& change : changes)
        if (!shape_ok(change)) return false;
    std::vector<std::uint32_t> excluded = removed;
    for (const Change& change : changes) excluded.push_back(change.slot);
    return fans_in_order(changes, excluded) && clear_of_others(changes, excluded);
}

} // namespace tissuemesh::surface::detail

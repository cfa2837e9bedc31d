#include "surface/detail/complex_editor.h"

#include <algorithm>
#include <cmath>

#include "surface/detail/cgal_intersections.h"
#include "surface/detail/edit_rules.h"
#include "surface/detail/mesh_measures.h"

namespace tissuemesh::surface::detail {
namespace {

/// Canonical orientation of a patch: the larger label behind, except that the background is always in front.
bool canonical(const LabelPair& side, Label background)
{
    if (side.to == background) return true;
    if (side.from == background) return false;
    return side.from > side.to;
}

/// Rotates t so that it starts with v.
Triangle starting_at(const Triangle& t, std::uint32_t v)
{
    if (t[1] == v) return {t[1], t[2], t[0]};
    if (t[2] == v) return {t[2], t[0], t[1]};
    return t;
}

} // namespace

ComplexEditor::ComplexEditor(InterfaceComplex complex, const EditLimits& limits, double cell_mm)
    : limits_(limits), min_angle_(limits.min_angle_deg), max_tilt_(limits.max_normal_change_deg), positions_(std::move(complex.vertices)), triangles_(std::move(complex.triangles)),
      sides_(std::move(complex.sides)), alive_(triangles_.size(), 1), stars_(positions_.size()),
      kinds_(positions_.size(), VertexKind::corner), alive_triangles_(triangles_.size())
{
    background_ = complex.background;
    names_ = std::move(complex.names);
    for (std::uint32_t t = 0; t < triangles_.size(); ++t) {
        if (!canonical(sides_[t], background_)) {
            std::swap(triangles_[t][1], triangles_[t][2]);
            std::swap(sides_[t].from, sides_[t].to);
        }
        for (const std::uint32_t v : triangles_[t]) stars_[v].push_back(t);
    }
    for (std::uint32_t v = 0; v < positions_.size(); ++v) kinds_[v] = classify(v);
    rebuild_grid(cell_mm);
}

void ComplexEditor::rebuild_grid(double cell_mm)
{
    grid_cell_mm_ = cell_mm;
    grid_ = TriangleGrid();
    grid_ready_ = false;
    boxes_.assign(triangles_.size(), CompactBox{});
    for (std::uint32_t t = 0; t < triangles_.size(); ++t)
        if (alive_[t]) boxes_[t] = compact(bounding_box(corners(t)));
}

void ComplexEditor::ensure_grid()
{
    if (grid_ready_) return;
    Box3 bounds{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
    for (std::uint32_t v = 0; v < positions_.size(); ++v) {
        if (!vertex_alive(v)) continue;
        for (int i = 0; i < 3; ++i) {
            bounds.low[i] = std::min(bounds.low[i], positions_[v][i]);
            bounds.high[i] = std::max(bounds.high[i], positions_[v][i]);
        }
    }
    if (bounds.low[0] > bounds.high[0]) bounds = Box3{};
    grid_ = TriangleGrid(bounds, grid_cell_mm_, triangles_.size());
    for (std::uint32_t t = 0; t < triangles_.size(); ++t)
        if (alive_[t]) grid_.insert(t, bounding_box(corners(t)));
    grid_ready_ = true;
}

TriangleCorners ComplexEditor::corners(std::uint32_t t) const
{
    const Triangle& tri = triangles_[t];
    return {positions_[tri[0]], positions_[tri[1]], positions_[tri[2]]};
}

double ComplexEditor::mean_edge_length() const
{
    double sum = 0;
    for (std::uint32_t t = 0; t < triangles_.size(); ++t)
        if (alive_[t]) sum += distance(positions_[triangles_[t][0]], positions_[triangles_[t][1]]);
    return alive_triangles_ == 0 ? 1.0 : sum / static_cast<double>(alive_triangles_);
}

std::vector<std::uint32_t> ComplexEditor::neighbours(std::uint32_t v) const
{
    std::vector<std::uint32_t> result;
    for (const std::uint32_t t : stars_[v])
        for (const std::uint32_t u : triangles_[t])
            if (u != v) result.push_back(u);
    std::sort(result.begin(), result.end());
    result.erase(std::unique(result.begin(), result.end()), result.end());
    return result;
}

void ComplexEditor::ring(std::uint32_t v, std::vector<RingEntry>& out) const
{
    out.clear();
    // A star has a few dozen entries at most: a linear search beats sorting.
    for (const std::uint32_t t : stars_[v])
        for (const std::uint32_t u : triangles_[t]) {
            if (u == v) continue;
            auto it = out.begin();
            while (it != out.end() && it->vertex != u) ++it;
            if (it == out.end()) out.push_back({u, 1});
            else ++it->triangles;
        }
}

std::size_t ComplexEditor::edge_multiplicity(std::uint32_t v, std::uint32_t w) const
{
    std::size_t count = 0;
    for (const std::uint32_t t : stars_[v]) count += contains(triangles_[t], w) ? 1 : 0;
    return count;
}

std::vector<std::uint32_t> ComplexEditor::curve_neighbours(std::uint32_t v) const
{
    std::vector<std::uint32_t> result;
    for (const std::uint32_t u : neighbours(v))
        if (edge_multiplicity(v, u) >= 3) result.push_back(u);
    return result;
}

/// patch: one closed fan of one patch (every edge at v shared by two triangles of that patch);
/// curve: exactly two junction edges, every other edge shared by two triangles; corner: anything else.
VertexKind ComplexEditor::classify(std::uint32_t v) const
{
    const auto& star = stars_[v];
    if (star.empty()) return VertexKind::corner;
    thread_local std::vector<RingEntry> around;
    ring(v, around);
    std::size_t junction = 0;
    for (const RingEntry& e : around) {
        if (e.triangles >= 3) ++junction;
        else if (e.triangles != 2) return VertexKind::corner;
    }
    if (junction == 2) return VertexKind::curve;
    if (junction != 0) return VertexKind::corner;
    const LabelPair first = sides_[star.front()];
    for (const std::uint32_t t : star)
        if (!(sides_[t] == first)) return VertexKind::corner;
    // A single fan: as many distinct neighbours as triangles (two fans touching at v would share none).
    return around.size() == star.size() ? VertexKind::patch : VertexKind::corner;
}

void ComplexEditor::update_kinds(std::uint32_t v)
{
    kinds_[v] = classify(v);
    thread_local std::vector<RingEntry> around;
    ring(v, around);
    for (const RingEntry& e : around) kinds_[e.vertex] = classify(e.vertex);
}

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
bool ComplexEditor::meet(const Triangle& a, const TriangleCorners& pa, const Triangle& b, const TriangleCorners& pb) const
{
    if (certainly_apart(a, pa, b, pb)) return false;
    return triangles_intersect(positions_, a, b);
}

bool ComplexEditor::clear_of_others(const std::vector<Change>& changes, const std::vector<std::uint32_t>& excluded)
{
    const double gap = limits_.min_gap_mm;
    thread_local std::vector<TriangleCorners> shapes;  // scratch: an edit changes a few triangles
    thread_local std::vector<Box3> boxes;
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
    thread_local std::vector<const TriangleCorners*> before;
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
            if (closes_wedge(changes[i].triangle, shapes[i], before[j] ? before[i] : nullptr, changes[j].triangle, shapes[j],
                             changes[j].before, limits_.min_wedge_deg)) {
                ++counters_.wedge;
                return false;
            }
        }
    grid_.query(all, nearby_);
    for (const std::uint32_t t : nearby_) {
        if (!alive_[t] || !boxes_overlap(all, boxes_[t]) ||
            std::find(excluded.begin(), excluded.end(), t) != excluded.end())
            continue;
        const TriangleCorners cb = corners(t);
        const Box3 box = bounding_box(cb);
        if (!boxes_overlap(all, box)) continue;
        for (std::size_t i = 0; i < changes.size(); ++i) {
            if (!boxes_overlap(boxes[i], box)) continue;
            const Triangle& a = changes[i].triangle;
            if ((same_vertex_set(a, triangles_[t]) || meet(a, shapes[i], triangles_[t], cb)) && meets())
                return false;
            if (shares_vertex(a, triangles_[t]) && closes_wedge(a, shapes[i], before[i], triangles_[t], cb, cb, limits_.min_wedge_deg)) {
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
            if (same_vertex_set(triangles_[s], triangles_[t]) || triangles_intersect(positions_, triangles_[s], triangles_[t]))
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

bool ComplexEditor::acceptable(const std::vector<Change>& changes, const std::vector<std::uint32_t>& removed)
{
    for (const Change& change : changes)
        if (!shape_ok(change)) return false;
    std::vector<std::uint32_t> excluded = removed;
    for (const Change& change : changes) excluded.push_back(change.slot);
    return clear_of_others(changes, excluded);
}

void ComplexEditor::apply(const std::vector<Change>& changes, const std::vector<std::uint32_t>& removed)
{
    batch_index_valid_ = false;
    for (const std::uint32_t t : removed) {
        grid_.erase(t, bounding_box(corners(t)));
        for (const std::uint32_t v : triangles_[t]) std::erase(stars_[v], t);
        alive_[t] = 0;
        --alive_triangles_;
    }
    for (const Change& change : changes) {
        const std::uint32_t t = change.slot;
        if (t < triangles_.size() && alive_[t]) {
            grid_.erase(t, bounding_box(change.before));
            for (const std::uint32_t v : triangles_[t]) std::erase(stars_[v], t);
        } else {
            if (t >= triangles_.size()) {
                triangles_.resize(t + 1);
                sides_.resize(t + 1);
                alive_.resize(t + 1, 0);
            }
            ++alive_triangles_;
        }
        triangles_[t] = change.triangle;
        alive_[t] = 1;
        for (const std::uint32_t v : change.triangle) stars_[v].push_back(t);
        const Box3 box = bounding_box(corners(t));
        grid_.insert(t, box);
        if (t >= boxes_.size()) boxes_.resize(static_cast<std::size_t>(t) + 1 + boxes_.size() / 2);
        boxes_[t] = compact(box);
    }
    ++counters_.accepted;
}

bool ComplexEditor::try_move(std::uint32_t v, const Vec3& p)
{
    if (!vertex_alive(v)) return false;
    ensure_grid();
    set_budget(stars_[v]);
    std::vector<Change> changes;
    for (const std::uint32_t t : stars_[v]) changes.push_back({t, triangles_[t], corners(t)});
    const Vec3 old = positions_[v];
    positions_[v] = p;
    if (!acceptable(changes, {})) {
        positions_[v] = old;
        return false;
    }
    // apply() re-files each triangle in the grid: erase by the old box, insert by the new one.
    apply(changes, {});
    return true;
}

bool ComplexEditor::try_move_group(const std::vector<std::uint32_t>& vertices, const std::vector<Vec3>& positions)
{
    std::vector<std::uint32_t> slots;
    for (const std::uint32_t v : vertices) slots.insert(slots.end(), stars_[v].begin(), stars_[v].end());
    std::sort(slots.begin(), slots.end());
    slots.erase(std::unique(slots.begin(), slots.end()), slots.end());
    if (slots.empty()) return false;
    ensure_grid();
    set_budget(slots);
    std::vector<Change> changes;
    for (const std::uint32_t t : slots) changes.push_back({t, triangles_[t], corners(t)});
    std::vector<Vec3> old;
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        old.push_back(positions_[vertices[i]]);
        positions_[vertices[i]] = positions[i];
    }
    if (!acceptable(changes, {})) {
        for (std::size_t i = vertices.size(); i-- > 0;) positions_[vertices[i]] = old[i];
        return false;
    }
    apply(changes, {});
    return true;
}

/// Lk(v) n Lk(w) = Lk(vw): the common neighbours are exactly the third vertices of triangles on vw, and
/// no edge ab has both triangles vab and wab. Plus the interface rule that merged edges keep their
/// multiplicity (no two junction edges fuse).
bool ComplexEditor::link_condition(std::uint32_t v, std::uint32_t w) const
{
    thread_local std::vector<RingEntry> nv, nw;
    thread_local std::vector<std::uint32_t> apexes;
    ring(v, nv);
    ring(w, nw);
    apexes.clear();
    for (const std::uint32_t t : stars_[v])
        if (contains(triangles_[t], w))
            for (const std::uint32_t u : triangles_[t])
                if (u != v && u != w && std::find(apexes.begin(), apexes.end(), u) == apexes.end()) apexes.push_back(u);
    // The common neighbours must be the apexes (each list holds distinct vertices); meanwhile note whether
    // some common neighbour's edges to v and w are not both ordinary.
    std::size_t common = 0;
    bool fused = false;
    for (const RingEntry& a : nv)
        for (const RingEntry& b : nw)
            if (a.vertex == b.vertex) {
                if (std::find(apexes.begin(), apexes.end(), a.vertex) == apexes.end()) return false;
                ++common;
                fused = fused || std::min(a.triangles, b.triangles) != 2;
            }
    if (common != apexes.size()) return false;
    // Edges vx and wx merge; at most one of them may be a junction edge, or two junction curves would
    // fuse into an edge where a tissue touches itself (x runs over the apexes, now the common neighbours).
    if (fused) return false;
    for (const std::uint32_t t : stars_[v]) {
        const Triangle r = starting_at(triangles_[t], v);
        if (r[1] == w || r[2] == w) continue;
        for (const std::uint32_t s : stars_[w])
            if (contains(triangles_[s], r[1]) && contains(triangles_[s], r[2])) return false;
    }
    return true;
}

bool ComplexEditor::try_collapse(std::uint32_t v, std::uint32_t w, const std::function<bool()>& veto)
{
    if (v == w || !vertex_alive(v) || !vertex_alive(w)) return false;
    const std::size_t multiplicity = edge_multiplicity(v, w);
    const bool allowed = multiplicity > 0 && kinds_[v] != VertexKind::corner &&
                         (kinds_[v] == VertexKind::patch || multiplicity >= 3);
    if (!allowed) {
        ++counters_.topology;
        return false;
    }
    ensure_grid();
    thread_local std::vector<std::uint32_t> removed, excluded;  // scratch: collapses are tried millions of times
    thread_local std::vector<Change> changes;
    removed.clear();
    changes.clear();
    for (const std::uint32_t t : stars_[v]) {
        if (contains(triangles_[t], w)) {
            removed.push_back(t);
            continue;
        }
        Triangle moved = triangles_[t];
        std::replace(moved.begin(), moved.end(), v, w);
        changes.push_back({t, moved, corners(t)});
    }
    // Most refused collapses fold or squeeze a triangle (on raw terraces 15 for every one the link
    // condition refuses): those tests go first, the grid search last.
    for (const Change& change : changes)
        if (!shape_ok(change)) return false;
    if (!link_condition(v, w)) {
        ++counters_.topology;
        return false;
    }
    if (veto && !veto()) return false;
    set_budget(stars_[v]);
    excluded = removed;
    for (const Change& change : changes) excluded.push_back(change.slot);
    if (!clear_of_others(changes, excluded)) return false;
    apply(changes, removed);
    update_kinds(w);
    return true;
}

std::uint32_t ComplexEditor::add_vertex(const Vec3& p)
{
    positions_.push_back(p);
    stars_.emplace_back();
    kinds_.push_back(VertexKind::corner);
    return static_cast<std::uint32_t>(positions_.size() - 1);
}

std::optional<std::uint32_t> ComplexEditor::try_split(std::uint32_t v, std::uint32_t w, const Vec3& p)
{
    std::vector<std::uint32_t> on_edge;
    for (const std::uint32_t t : stars_[v])
        if (contains(triangles_[t], w)) on_edge.push_back(t);
    if (on_edge.empty()) return std::nullopt;
    ensure_grid();
    set_budget(on_edge);
    const std::uint32_t m = add_vertex(p);
    std::vector<Change> changes;
    auto next_slot = static_cast<std::uint32_t>(triangles_.size());
    for (const std::uint32_t t : on_edge) {
        Triangle first = triangles_[t], second = triangles_[t];
        std::replace(first.begin(), first.end(), w, m);
        std::replace(second.begin(), second.end(), v, m);
        changes.push_back({t, first, corners(t)});
        changes.push_back({next_slot++, second, corners(t), sides_[t]});
    }
    if (!acceptable(changes, {})) {
        positions_.pop_back();
        stars_.pop_back();
        kinds_.pop_back();
        return std::nullopt;
    }
    for (std::size_t i = 1; i < changes.size(); i += 2) {
        const std::uint32_t t = changes[i].slot;
        triangles_.resize(t + 1);
        alive_.resize(t + 1, 0);
        sides_.resize(t + 1);
        sides_[t] = sides_[changes[i - 1].slot];
    }
    apply(changes, {});
    update_kinds(m);
    return m;
}

bool ComplexEditor::try_flip(std::uint32_t v, std::uint32_t w)
{
    std::vector<std::uint32_t> on_edge;
    for (const std::uint32_t t : stars_[v])
        if (contains(triangles_[t], w)) on_edge.push_back(t);
    if (on_edge.size() != 2 || !(sides_[on_edge[0]] == sides_[on_edge[1]])) {
        ++counters_.topology;
        return false;
    }
    // Orient: first = (v, w, a), second = (w, v, b).
    std::uint32_t t1 = on_edge[0], t2 = on_edge[1];
    if (starting_at(triangles_[t1], v)[1] != w) std::swap(t1, t2);
    const Triangle r1 = starting_at(triangles_[t1], v), r2 = starting_at(triangles_[t2], w);
    if (r1[1] != w || r2[1] != v) {
        ++counters_.topology;
        return false;
    }
    const std::uint32_t a = r1[2], b = r2[2];
    const auto fan_size = [&](std::uint32_t u) {
        std::size_t n = 0;
        for (const std::uint32_t t : stars_[u]) n += sides_[t] == sides_[t1] ? 1 : 0;
        return n;
    };
    const auto keeps_fan = [&](std::uint32_t u) {
        return kinds_[u] == VertexKind::patch ? stars_[u].size() > 3 : fan_size(u) > 1;
    };
    if (a == b || edge_multiplicity(a, b) != 0 || !keeps_fan(v) || !keeps_fan(w)) {
        ++counters_.topology;
        return false;
    }
    ensure_grid();
    set_budget(on_edge);
    const TriangleCorners before1 = corners(t1), before2 = corners(t2);
    std::vector<Change> changes{{t1, {v, b, a}, before1}, {t2, {w, a, b}, before2}};
    // Each new triangle must not tilt much from either old one (no flipping across a crease).
    if (!acceptable(changes, {})) return false;
    std::vector<Change> swapped{{t1, {v, b, a}, before2}, {t2, {w, a, b}, before1}};
    for (const Change& change : swapped)
        if (!shape_ok(change)) return false;
    apply(changes, {});
    for (const std::uint32_t u : {v, w, a, b}) kinds_[u] = classify(u);
    return true;
}

InterfaceComplex ComplexEditor::result() const
{
    InterfaceComplex out;
    out.background = background_;
    out.names = names_;
    std::vector<std::uint32_t> index(positions_.size(), 0);
    for (std::uint32_t v = 0; v < positions_.size(); ++v) {
        if (!vertex_alive(v)) continue;
        index[v] = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.push_back(positions_[v]);
    }
    for (std::uint32_t t = 0; t < triangles_.size(); ++t) {
        if (!alive_[t]) continue;
        const Triangle& tri = triangles_[t];
        out.add_triangle({index[tri[0]], index[tri[1]], index[tri[2]]}, sides_[t]);
    }
    return out;
}

std::vector<Label> tissues_around(const ComplexEditor& editor, std::uint32_t v)
{
    std::vector<Label> tissues;
    for (const std::uint32_t t : editor.star(v)) tissues.insert(tissues.end(), {editor.side(t).from, editor.side(t).to});
    std::sort(tissues.begin(), tissues.end());
    tissues.erase(std::unique(tissues.begin(), tissues.end()), tissues.end());
    return tissues;
}

} // namespace tissuemesh::surface::detail

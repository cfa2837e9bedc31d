#include "surface/detail/complex_editor.h"

#include <algorithm>
#include <cmath>

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

} // namespace

ComplexEditor::ComplexEditor(InterfaceComplex complex, const EditLimits& limits, double cell_mm)
    : EditableComplex(std::move(complex)), limits_(limits), min_angle_(limits.min_angle_deg),
      max_tilt_(limits.max_normal_change_deg)
{
    for (std::uint32_t t = 0; t < triangles_.size(); ++t)
        if (!canonical(sides_[t], background_)) {
            std::swap(triangles_[t][1], triangles_[t][2]);
            std::swap(sides_[t].from, sides_[t].to);
        }
    classify_all();
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

void ComplexEditor::apply(const std::vector<Change>& changes, const std::vector<std::uint32_t>& removed)
{
    batch_index_valid_ = false;
    for (const std::uint32_t t : removed) {
        grid_.erase(t, bounding_box(corners(t)));
        for (const std::uint32_t v : triangles_[t]) std::erase(stars_[v], t);
        alive_[t] = 0;
        --alive_count_;
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
            ++alive_count_;
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

bool ComplexEditor::try_collapse(std::uint32_t v, std::uint32_t w, const std::function<bool()>& veto)
{
    if (v == w || !vertex_alive(v) || !vertex_alive(w)) return false;
    const std::size_t multiplicity = edge_multiplicity(v, w);
    const bool allowed =
        multiplicity > 0 && kinds_[v] != VertexKind::corner && (kinds_[v] == VertexKind::patch || multiplicity >= 3);
    if (!allowed) {
        ++counters_.topology;
        return false;
    }
    ensure_grid();
    std::vector<std::uint32_t>& removed = collapse_removed_;
    std::vector<std::uint32_t>& excluded = collapse_excluded_;
    std::vector<Change>& changes = collapse_changes_;
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
    if (!fans_in_order(changes, excluded) || !clear_of_others(changes, excluded)) return false;
    apply(changes, removed);
    // Only w and the common neighbours of v and w (the third vertices of the triangles on vw) can change
    // kind: any other neighbour of v trades its edge to v for one to w with the same triangles on it.
    std::vector<std::uint32_t>& common = collapse_common_;
    common.clear();
    for (const std::uint32_t t : removed)
        for (const std::uint32_t u : triangles_[t])
            if (u != v && u != w) common.push_back(u);
    reclassify(w, &common);
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
    reclassify(m);
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

} // namespace tissuemesh::surface::detail

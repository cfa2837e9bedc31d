#include "surface/detail/local_editor.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "core/error.h"
#include "surface/detail/cgal_intersections.h"
#include "surface/detail/edge_fan.h"
#include "surface/detail/local_geometry.h"
#include "surface/detail/star_check.h"
#include "surface/detail/triangle_distance.h"

namespace tissuemesh::surface::detail {
constexpr double pi = 3.14159265358979323846;

LocalEditor::LocalEditor(InterfaceComplex complex, const LocalLimits& limits, double cell_mm)
    : EditableComplex(std::move(complex)), cell_mm_(cell_mm)
{
    set_limits(limits);
    if (!(cell_mm > 0)) cell_mm = 1;
    classify_all();
    filed_.resize(triangles_.size());
    stamp_.assign(triangles_.size(), 0);
    rebuild_grid(cell_mm);
    count_pieces();
}

void LocalEditor::count_pieces()
{
    // Union-find over (triangle, side), joined at each vertex per tissue.
    std::vector<std::uint32_t> parent(2 * triangles_.size());
    for (std::uint32_t n = 0; n < parent.size(); ++n) parent[n] = n;
    const auto find = [&](std::uint32_t n) {
        while (parent[n] != n) n = parent[n] = parent[parent[n]];
        return n;
    };
    std::vector<std::pair<Label, std::uint32_t>> first; // per tissue at the vertex: its first (triangle, side)
    for (std::uint32_t v = 0; v < stars_.size(); ++v) {
        first.clear();
        for (const std::uint32_t t : stars_[v]) {
            if (!alive_[t]) continue;
            for (std::uint32_t s = 0; s < 2; ++s) {
                const Label tissue = s == 0 ? sides_[t].from : sides_[t].to;
                if (tissue == background_) continue;
                const auto it =
                    std::find_if(first.begin(), first.end(), [&](const auto& f) { return f.first == tissue; });
                if (it == first.end()) {
                    first.emplace_back(tissue, 2 * t + s);
                    continue;
                }
                const std::uint32_t a = find(it->second), b = find(2 * t + s);
                if (a != b) parent[std::max(a, b)] = std::min(a, b);
            }
        }
    }
    piece_of_.assign(triangles_.size(), {no_piece, no_piece});
    piece_size_.clear();
    std::vector<std::uint32_t> id(parent.size(), no_piece);
    for (std::uint32_t t = 0; t < triangles_.size(); ++t) {
        if (!alive_[t]) continue;
        for (std::uint32_t s = 0; s < 2; ++s) {
            if ((s == 0 ? sides_[t].from : sides_[t].to) == background_) continue;
            std::uint32_t& piece = id[find(2 * t + s)];
            if (piece == no_piece) piece = static_cast<std::uint32_t>(piece_size_.size()), piece_size_.push_back(0);
            piece_of_[t][s] = piece;
            ++piece_size_[piece];
        }
    }
}

std::size_t LocalEditor::counted_piece(std::uint32_t v, Label tissue) const
{
    for (const std::uint32_t t : stars_[v]) {
        const std::size_t s = sides_[t].from == tissue ? 0 : sides_[t].to == tissue ? 1 : 2;
        if (s < 2 && piece_of_[t][s] != no_piece) return piece_size_[piece_of_[t][s]];
    }
    return 0;
}

void LocalEditor::recount(std::uint32_t t, int delta)
{
    for (const std::uint32_t piece : piece_of_[t])
        if (piece != no_piece) {
            saved_piece_sizes_.emplace_back(piece, piece_size_[piece]);
            piece_size_[piece] = static_cast<std::uint32_t>(static_cast<std::int64_t>(piece_size_[piece]) + delta);
        }
}

void LocalEditor::set_limits(const LocalLimits& limits)
{
    limits_ = limits;
    cos_min_angle_ = std::cos(limits.min_angle_deg * pi / 180);
    cos_max_tilt_ = std::cos(limits.max_tilt_deg * pi / 180);
    clear_sector_deg_ = limits.min_sector_deg + 1;
    cos_clear_sector_ = std::cos(clear_sector_deg_ * pi / 180);
}

void LocalEditor::rebuild_grid(double cell_mm)
{
    if (!(cell_mm > 0)) return;
    Vec3 low{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
             std::numeric_limits<double>::max()};
    Vec3 high = -1.0 * low;
    for (std::uint32_t v = 0; v < positions_.size(); ++v)
        if (!stars_[v].empty())
            for (int a = 0; a < 3; ++a)
                low[a] = std::min(low[a], positions_[v][a]), high[a] = std::max(high[a], positions_[v][a]);
    if (low[0] > high[0]) low = high = {0, 0, 0};
    cell_mm_ = cell_mm;
    const auto size = [&] {
        for (int a = 0; a < 3; ++a) {
            grid_origin_[a] = low[a] - 2 * cell_mm_;
            grid_dims_[a] = std::min<std::size_t>(60000, static_cast<std::size_t>((high[a] - low[a]) / cell_mm_) + 5);
        }
        return static_cast<double>(grid_dims_[0]) * static_cast<double>(grid_dims_[1]) *
               static_cast<double>(grid_dims_[2]);
    };
    // Keep the grid within memory's reach: cells grow when the box is large for the cell asked for.
    while (size() > 4e7) cell_mm_ *= 1.5;
    cells_.assign(grid_dims_[0] * grid_dims_[1] * grid_dims_[2], {});
    for (std::uint32_t t = 0; t < triangles_.size(); ++t)
        if (alive_[t]) file(t);
}

bool LocalEditor::shape_ok(const Triangle& now, const Triangle& before, bool check_tilt)
{
    const TriangleCorners a{positions_[now[0]], positions_[now[1]], positions_[now[2]]};
    const Vec3 na = cross(a[1] - a[0], a[2] - a[0]);
    const double scale =
        std::max({dot(a[1] - a[0], a[1] - a[0]), dot(a[2] - a[0], a[2] - a[0]), dot(a[2] - a[1], a[2] - a[1])});
    if (!(dot(na, na) > 1e-20 * scale * scale)) return false; // degenerate (or nearly so)
    const auto& b = before;
    const TriangleCorners c{positions_[b[0]], positions_[b[1]], positions_[b[2]]};
    if (check_tilt) {
        const Vec3 nb = cross(c[1] - c[0], c[2] - c[0]);
        if (dot(na, nb) < cos_max_tilt_ * norm(na) * norm(nb)) {
            ++counters_.normal;
            return false;
        }
    }
    const double cosine = smallest_angle_cosine(a);
    if (cosine > cos_min_angle_ && cosine > smallest_angle_cosine(c)) {
        ++counters_.shape;
        return false;
    }
    return true;
}

bool LocalEditor::inside_fence(const std::vector<std::uint32_t>& triangles) const
{
    if (!fence_) return true;
    for (const std::uint32_t t : triangles) {
        const Triangle& tri = triangles_[t];
        if (!fence_->holds(positions_[tri[0]], positions_[tri[1]], positions_[tri[2]])) return false;
    }
    return true;
}

LocalEditor::Box LocalEditor::box_of(const Triangle& t) const
{
    Box b{positions_[t[0]], positions_[t[0]]};
    for (int k = 1; k < 3; ++k)
        for (int a = 0; a < 3; ++a)
            b.low[a] = std::min(b.low[a], positions_[t[k]][a]), b.high[a] = std::max(b.high[a], positions_[t[k]][a]);
    return b;
}

std::uint16_t LocalEditor::cell_at(double x, int axis) const
{
    const double c = std::floor((x - grid_origin_[axis]) / cell_mm_);
    return static_cast<std::uint16_t>(std::clamp(c, 0.0, static_cast<double>(grid_dims_[axis] - 1)));
}

LocalEditor::CellRange LocalEditor::cells_of(const Triangle& t) const
{
    CellRange range{};
    for (int a = 0; a < 3; ++a) {
        double low = positions_[t[0]][a], high = low;
        for (int k = 1; k < 3; ++k)
            low = std::min(low, positions_[t[k]][a]), high = std::max(high, positions_[t[k]][a]);
        low -= limits_.min_gap_mm, high += limits_.min_gap_mm;
        const auto cell = [&](double x) {
            const double c = std::floor((x - grid_origin_[a]) / cell_mm_);
            return static_cast<std::uint16_t>(std::clamp(c, 0.0, static_cast<double>(grid_dims_[a] - 1)));
        };
        range[a] = cell(low);
        range[3 + a] = cell(high);
    }
    return range;
}

void LocalEditor::file(std::uint32_t t)
{
    const CellRange r = cells_of(triangles_[t]);
    filed_[t] = r;
    const Box box = box_of(triangles_[t]);
    const CellEntry entry{t, compact(Box3{box.low, box.high})};
    for (std::size_t k = r[2]; k <= r[5]; ++k)
        for (std::size_t j = r[1]; j <= r[4]; ++j)
            for (std::size_t i = r[0]; i <= r[3]; ++i)
                cells_[i + grid_dims_[0] * (j + grid_dims_[1] * k)].push_back(entry);
}

void LocalEditor::unfile(std::uint32_t t)
{
    const CellRange& r = filed_[t];
    for (std::size_t k = r[2]; k <= r[5]; ++k)
        for (std::size_t j = r[1]; j <= r[4]; ++j)
            for (std::size_t i = r[0]; i <= r[3]; ++i) {
                auto& cell = cells_[i + grid_dims_[0] * (j + grid_dims_[1] * k)];
                const auto it =
                    std::find_if(cell.begin(), cell.end(), [t](const CellEntry& e) { return e.triangle == t; });
                if (it != cell.end()) {
                    *it = cell.back();
                    cell.pop_back();
                }
            }
}

void LocalEditor::save_star(std::uint32_t v)
{
    saved_stars_.push_back(
        {v, static_cast<std::uint32_t>(saved_star_items_.size()), static_cast<std::uint32_t>(stars_[v].size())});
    saved_star_items_.insert(saved_star_items_.end(), stars_[v].begin(), stars_[v].end());
}

void LocalEditor::begin_edit()
{
    saved_.clear();
    saved_stars_.clear();
    saved_star_items_.clear();
    saved_piece_sizes_.clear();
    triangles_before_edit_ = triangles_.size();
    vertices_before_edit_ = positions_.size();
}

void LocalEditor::save(std::uint32_t t) { saved_.push_back({t, triangles_[t], alive_[t]}); }

void LocalEditor::remove_from_star(std::uint32_t v, std::uint32_t t)
{
    auto& star = stars_[v];
    const auto it = std::find(star.begin(), star.end(), t);
    if (it != star.end()) star.erase(it);
}

std::uint32_t LocalEditor::new_triangle(const Triangle& t, const LabelPair& side)
{
    triangles_.push_back(t);
    sides_.push_back(side);
    alive_.push_back(1);
    piece_of_.push_back({no_piece, no_piece});
    filed_.push_back({});
    stamp_.push_back(0);
    const auto id = static_cast<std::uint32_t>(triangles_.size() - 1);
    for (const std::uint32_t v : t) stars_[v].push_back(id);
    return id;
}

void LocalEditor::undo()
{
    for (auto it = saved_.rbegin(); it != saved_.rend(); ++it) {
        triangles_[it->triangle] = it->corners;
        alive_[it->triangle] = it->alive;
    }
    for (auto it = saved_stars_.rbegin(); it != saved_stars_.rend(); ++it)
        stars_[it->vertex].assign(saved_star_items_.begin() + it->start,
                                  saved_star_items_.begin() + it->start + it->size);
    for (auto it = saved_piece_sizes_.rbegin(); it != saved_piece_sizes_.rend(); ++it)
        piece_size_[it->first] = it->second;
    triangles_.resize(triangles_before_edit_);
    sides_.resize(triangles_before_edit_);
    alive_.resize(triangles_before_edit_);
    piece_of_.resize(triangles_before_edit_);
    filed_.resize(triangles_before_edit_);
    stamp_.resize(triangles_before_edit_);
    positions_.resize(vertices_before_edit_);
    stars_.resize(vertices_before_edit_);
    kinds_.resize(vertices_before_edit_);
}

bool LocalEditor::same_sheet_direction(std::uint32_t t, std::uint32_t u) const
{
    if (!(sides_[t] == sides_[u])) return false;
    const TriangleCorners a = corners(triangles_[t]), b = corners(triangles_[u]);
    const Vec3 na = cross(a[1] - a[0], a[2] - a[0]), nb = cross(b[1] - b[0], b[2] - b[0]);
    return dot(na, nb) > 0.8 * norm(na) * norm(nb);
}

bool LocalEditor::gap_ok(std::uint32_t t, const std::vector<Prior>& before, std::uint32_t other) const
{
    const TriangleCorners now = corners(triangles_[t]), q = corners(triangles_[other]);
    // Apart by more than the gap along some axis (their normals, the line between their centroids): no need
    // of the distance.
    const auto apart_along = [&](const Vec3& axis) {
        const double length = norm(axis);
        if (!(length > 0)) return false;
        const Vec3 d = (1 / length) * axis;
        const double a0 = dot(now[0], d), a1 = dot(now[1], d), a2 = dot(now[2], d);
        const double b0 = dot(q[0], d), b1 = dot(q[1], d), b2 = dot(q[2], d);
        return std::min({b0, b1, b2}) - std::max({a0, a1, a2}) > limits_.min_gap_mm ||
               std::min({a0, a1, a2}) - std::max({b0, b1, b2}) > limits_.min_gap_mm;
    };
    if (apart_along(cross(now[1] - now[0], now[2] - now[0])) || apart_along(cross(q[1] - q[0], q[2] - q[0])) ||
        apart_along((q[0] + q[1] + q[2]) - (now[0] + now[1] + now[2])))
        return true;
    const double distance_now = triangle_distance(now, q);
    if (distance_now >= limits_.min_gap_mm) return true;
    // Closer than the gap: allowed when it was at least as close before the edit.
    for (const Prior& b : before)
        if (b.first == t) return triangle_distance(b.second, q) <= distance_now;
    return false;
}

bool LocalEditor::fans_ok(const std::vector<std::uint32_t>& changed)
{
    std::vector<FanBlade>& blades = blades_;
    for (const std::uint32_t t : changed)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = triangles_[t][k], b = triangles_[t][(k + 1) % 3];
            if (a > b || edge_multiplicity(a, b) < 3) continue; // each junction edge once
            blades.clear();
            for (const std::uint32_t s : stars_[a])
                if (has(triangles_[s], b)) blades.push_back(blade_on(triangles_[s], a, b, positions_, sides_[s]));
            if (blades.size() >= 3 && fan_order(positions_[a], positions_[b], blades) != FanOrder::in_order)
                return false;
        }
    return true;
}

double LocalEditor::smallest_sector_deg(std::uint32_t a, std::uint32_t b, std::span<const FanBlade> blades) const
{
    const Vec3 e = positions_[b] - positions_[a];
    if (const double ee = dot(e, e); blades.size() == 2 && ee > 0) {
        // Two triangles: the smaller sector is the angle between their apexes' offsets across the edge. Most
        // edges are far from the limit; its cosine tells so without the two arc tangents.
        const Vec3 r = blades[0].apex - positions_[a], s = blades[1].apex - positions_[a];
        const Vec3 p = r - (dot(r, e) / ee) * e, q = s - (dot(s, e) / ee) * e;
        if (dot(p, q) < cos_clear_sector_ * std::sqrt(dot(p, p) * dot(q, q))) return clear_sector_deg_;
    }
    return detail::smallest_sector_deg(positions_[a], positions_[b], blades);
}

double LocalEditor::smallest_sector_deg(const std::vector<std::uint32_t>& triangles) const
{
    double smallest = 360;
    if (!(limits_.min_sector_deg > 0)) return smallest;
    // Each edge once, in the directions the triangles run along it (bit 1: low to high vertex; bit 2: back).
    std::vector<std::pair<std::uint64_t, int>>& edges = sector_edges_;
    edges.clear();
    for (const std::uint32_t t : triangles)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = triangles_[t][k], b = triangles_[t][(k + 1) % 3];
            edges.emplace_back(std::uint64_t{std::min(a, b)} << 32 | std::max(a, b), a < b ? 1 : 2);
        }
    std::sort(edges.begin(), edges.end());
    std::array<FanBlade, 16> blades{};
    for (std::size_t i = 0; i < edges.size();) {
        int directions = 0;
        const std::uint64_t key = edges[i].first;
        for (; i < edges.size() && edges[i].first == key; ++i) directions |= edges[i].second;
        const auto low = static_cast<std::uint32_t>(key >> 32), high = static_cast<std::uint32_t>(key);
        std::size_t count = 0;
        bool crowded = false; // more triangles than blades: no judgement
        for (const std::uint32_t t : stars_[low]) {
            if (!has(triangles_[t], high)) continue;
            if (count == blades.size()) {
                crowded = true;
                break;
            }
            blades[count++] = blade_on(triangles_[t], low, high, positions_, sides_[t]);
        }
        if (crowded) continue;
        const std::span<const FanBlade> fan(blades.data(), count);
        if (directions & 1) smallest = std::min(smallest, smallest_sector_deg(low, high, fan));
        if (directions & 2) smallest = std::min(smallest, smallest_sector_deg(high, low, fan));
    }
    return smallest;
}

bool LocalEditor::small_pieces(std::uint32_t v, std::vector<SmallPiece>& out, std::size_t margin,
                               std::span<const Label> known)
{
    constexpr std::size_t small_limit = 24;
    const std::size_t limit = small_limit + margin;
    bool clear = true;
    out.clear();
    if (vertex_stamp_.size() < positions_.size()) vertex_stamp_.resize(positions_.size(), 0);
    std::vector<std::uint32_t>& vertices = piece_vertices_;
    std::vector<std::uint32_t>& triangles = piece_triangles_;
    std::vector<Label>& seen = piece_tissues_;
    seen.clear();
    for (const std::uint32_t first : stars_[v])
        for (const Label tissue : {sides_[first].from, sides_[first].to}) {
            if (tissue == background_ || std::find(seen.begin(), seen.end(), tissue) != seen.end()) continue;
            seen.push_back(tissue);
            if (std::find(known.begin(), known.end(), tissue) != known.end()) continue;
            if (counted_piece(v, tissue) > limit) continue; // more than limit: clear of the margin
            // Breadth first through shared vertices over the triangles with `tissue` on a side, at most `limit`.
            ++query_;
            vertices.assign(1, v), triangles.clear();
            vertex_stamp_[v] = query_;
            bool complete = true; // the whole piece found within `limit` triangles
            for (std::size_t next = 0; next < vertices.size() && complete; ++next)
                for (const std::uint32_t t : stars_[vertices[next]]) {
                    if ((sides_[t].from != tissue && sides_[t].to != tissue) || stamp_[t] == query_) continue;
                    if (triangles.size() == limit) {
                        complete = false;
                        break;
                    }
                    stamp_[t] = query_;
                    triangles.push_back(t);
                    for (const std::uint32_t x : triangles_[t])
                        if (vertex_stamp_[x] != query_) vertex_stamp_[x] = query_, vertices.push_back(x);
                }
            if (!complete) continue; // more than limit: clear of the margin
            clear = false;
            if (triangles.size() > small_limit) continue; // all of it, within the margin but not small
            // Normals point from `from` into `to`: outward where the tissue is `from`.
            SmallPiece piece{tissue, 0, 0};
            const Vec3 origin = positions_[v];
            for (const std::uint32_t t : triangles) {
                const TriangleCorners c = corners(triangles_[t]);
                const double sign = sides_[t].from == tissue ? 1 : -1;
                piece.volume += sign * dot(cross(c[1] - origin, c[2] - origin), c[0] - origin) / 6;
                piece.area += norm(cross(c[1] - c[0], c[2] - c[0])) / 2;
            }
            out.push_back(piece);
        }
    return clear;
}

template <typename Near, typename Visit>
bool LocalEditor::any_in_cells(const CellRange& r, const Box& box, const Near& near, const Visit& visit)
{
    // The entries' boxes first: most triangles of a cell are far from the box, and they are in the cell's own
    // memory, where the triangles' own are scattered.
    const Box3 bounds{box.low, box.high};
    for (std::size_t k = r[2]; k <= r[5]; ++k)
        for (std::size_t j = r[1]; j <= r[4]; ++j)
            for (std::size_t i = r[0]; i <= r[3]; ++i)
                for (const CellEntry& e : cells_[i + grid_dims_[0] * (j + grid_dims_[1] * k)]) {
                    if (!boxes_overlap(bounds, e.box) || !near(e.box)) continue;
                    const std::uint32_t u = e.triangle;
                    if (stamp_[u] == query_ || !alive_[u]) continue;
                    stamp_[u] = query_;
                    if (visit(u, e.box)) return true;
                }
    return false;
}

bool LocalEditor::path_crosses(std::uint32_t v, const Vec3& from, const Vec3& to)
{
    Box path{};
    CellRange r{};
    for (int a = 0; a < 3; ++a) {
        path.low[a] = std::min(from[a], to[a]), path.high[a] = std::max(from[a], to[a]);
        r[a] = cell_at(path.low[a], a), r[3 + a] = cell_at(path.high[a], a);
    }
    ++query_;
    return any_in_cells(
        r, path, [](const CompactBox&) { return true; },
        [&](std::uint32_t u, const CompactBox&) {
            const Triangle& tri = triangles_[u];
            if (has(tri, v) || !overlap(box_of(tri), path)) return false;
            const Vec3 &p = positions_[tri[0]], &q = positions_[tri[1]], &s = positions_[tri[2]];
            const int side_from = orientation(p, q, s, from), side_to = orientation(p, q, s, to);
            if (side_from * side_to > 0 || (side_from == 0 && side_to == 0)) return false;
            const int e0 = orientation(from, to, p, q), e1 = orientation(from, to, q, s),
                      e2 = orientation(from, to, s, p);
            return (e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0);
        });
}

bool LocalEditor::surroundings_ok(const std::vector<std::uint32_t>& changed, const std::vector<Prior>& before)
{
    // Triangles sharing no vertex with a changed one: from the grid (one query over the box of all the
    // changed triangles), each judged against every changed triangle whose box it comes within the gap of.
    const double gap = limits_.min_gap_mm;
    std::vector<Box>& boxes = boxes_;
    boxes.clear();
    Box all{
        {std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), std::numeric_limits<double>::max()},
        {std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest(),
         std::numeric_limits<double>::lowest()}};
    for (const std::uint32_t t : changed) {
        Box& b = boxes.emplace_back(box_of(triangles_[t]));
        for (int a = 0; a < 3; ++a) {
            b.low[a] -= gap, b.high[a] += gap;
            all.low[a] = std::min(all.low[a], b.low[a]), all.high[a] = std::max(all.high[a], b.high[a]);
        }
    }
    CellRange r{};
    for (int a = 0; a < 3; ++a) r[a] = cell_at(all.low[a], a), r[3 + a] = cell_at(all.high[a], a);
    ++query_;
    for (const std::uint32_t t : changed) stamp_[t] = query_;
    // A triangle not changed by the edit is judged by the box it was filed with, as the grid holds it (in single
    // precision, rounded outwards: a few more pairs judged, the same answers).
    const auto near_changed = [&](const CompactBox& ub, std::size_t n) {
        const Box& b = boxes[n];
        return !(ub.high[0] < b.low[0] || b.high[0] < ub.low[0] || ub.high[1] < b.low[1] || b.high[1] < ub.low[1] ||
                 ub.high[2] < b.low[2] || b.high[2] < ub.low[2]);
    };
    const auto near = [&](const CompactBox& ub) {
        for (std::size_t n = 0; n < changed.size(); ++n)
            if (near_changed(ub, n)) return true;
        return false;
    };
    const bool offender = any_in_cells(r, all, near, [&](std::uint32_t u, const CompactBox& ub) {
        for (std::size_t n = 0; n < changed.size(); ++n) {
            const std::uint32_t t = changed[n];
            if (!near_changed(ub, n) || share_vertex(triangles_[t], triangles_[u])) continue;
            if (triangles_meet(positions_, triangles_[t], triangles_[u])) {
                ++counters_.intersection;
                return true;
            }
            if (gap > 0 && !same_sheet_direction(t, u) && !gap_ok(t, before, u)) {
                ++counters_.gap;
                return true;
            }
        }
        return false;
    });
    if (offender) return false;
    // Triangles sharing a vertex with a changed one: the stars of their vertices.
    std::vector<std::uint32_t>& vertices = star_vertices_;
    vertices.clear();
    for (const std::uint32_t t : changed)
        for (const std::uint32_t v : triangles_[t]) vertices.push_back(v);
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    for (const std::uint32_t v : vertices)
        if (!star_is_clean(v, stars_[v], positions_, triangles_, changed)) {
            ++counters_.intersection;
            return false;
        }
    if (!fans_ok(changed)) {
        ++counters_.wedge;
        return false;
    }
    return true;
}

} // namespace tissuemesh::surface::detail

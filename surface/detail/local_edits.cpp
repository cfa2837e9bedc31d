// The edits of LocalEditor: collapse, split, flip and move, each applied, judged where it happens
// (local_editor.h), and undone when refused.
#include "surface/detail/local_editor.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "surface/detail/local_geometry.h"

namespace tissuemesh::surface::detail {

namespace {

/// A small closed piece may shrink, but not below this fraction of its volume in one edit: flattened to 1e-15
/// mm^3 it passes every check and leaves TetGen a tet of no volume between its faces.
constexpr double flat_shell_ratio = 1e-3;

/// Nor may an edit leave it thinner than this volume over area^1.5 (a cube 0.068, a regular tet 0.052; of
/// random tets, those above 0.02 all have dihedral angles of 6 degrees or more), unless it was thinner
/// before and gets no thinner: a sliver-shaped pocket can only be meshed with sliver tets.
constexpr double fat_piece_ratio = 0.02;

double fatness(const SmallPiece& p) { return p.area > 0 ? std::abs(p.volume) / std::pow(p.area, 1.5) : 0; }

/// Whether the small pieces after an edit are as fit to be meshed as before: each piece small before keeps
/// its sign, a share of its volume and its fatness (or stays above fat_piece_ratio); a piece small only
/// after is fat.
bool pieces_ok(const std::vector<SmallPiece>& before, const std::vector<SmallPiece>& after)
{
    for (const SmallPiece& b : before) {
        const auto a =
            std::find_if(after.begin(), after.end(), [&](const SmallPiece& p) { return p.tissue == b.tissue; });
        if (a == after.end() || !(a->volume / b.volume > flat_shell_ratio)) return false;
        if (fatness(*a) < fat_piece_ratio && fatness(*a) < fatness(b)) return false;
    }
    for (const SmallPiece& a : after)
        if (std::none_of(before.begin(), before.end(), [&](const SmallPiece& p) { return p.tissue == a.tissue; }) &&
            fatness(a) < fat_piece_ratio)
            return false;
    return true;
}

} // namespace

void LocalEditor::keep_prior()
{
    edit_.prior.clear();
    for (const std::uint32_t t : edit_.changed) edit_.prior.emplace_back(t, corners(triangles_[t]));
}

template <class Before>
bool LocalEditor::judge_merge(std::uint32_t kept, Before sectors_before, bool pieces_clear)
{
    if (!sectors_ok(stars_[kept], sectors_before) || !surroundings_ok(edit_.changed, edit_.prior)) {
        undo();
        return false;
    }
    if (!pieces_clear &&
        (small_pieces(kept, edit_.pieces_after), !pieces_ok(edit_.pieces_before, edit_.pieces_after))) {
        ++counters_.topology;
        undo();
        return false;
    }
    for (const std::uint32_t t : edit_.dying) unfile(t);
    for (const std::uint32_t t : edit_.changed) {
        unfile(t);
        file(t);
    }
    alive_count_ -= edit_.dying.size();
    return true;
}

bool LocalEditor::try_collapse(std::uint32_t v, std::uint32_t w, const std::function<bool()>& veto)
{
    if (v == w || !vertex_alive(v) || !vertex_alive(w)) return false;
    const std::uint32_t on_edge = edge_multiplicity(v, w);
    if (on_edge == 0) return false;
    // Junction rules: corners stay; a curve vertex goes only along its curve.
    if (kinds_[v] == VertexKind::corner || (kinds_[v] == VertexKind::curve && on_edge < 3)) {
        ++counters_.topology;
        return false;
    }
    // Link condition: every common neighbour is the apex of a triangle on vw, and no two common neighbours
    // x, y have both vxy and wxy (the collapse would make them one).
    std::vector<RingEntry>& around_v = edit_.around_v;
    std::vector<RingEntry>& around_w = edit_.around_w;
    ring(v, around_v);
    ring(w, around_w);
    std::vector<std::uint32_t>& common = edit_.common;
    common.clear();
    for (const RingEntry& n : around_v)
        if (n.vertex != w &&
            std::any_of(around_w.begin(), around_w.end(), [&](const RingEntry& m) { return m.vertex == n.vertex; }))
            common.push_back(n.vertex);
    const auto triangle_with = [&](std::uint32_t a, std::uint32_t x, std::uint32_t y) {
        return std::any_of(stars_[a].begin(), stars_[a].end(),
                           [&](std::uint32_t t) { return has(triangles_[t], x) && has(triangles_[t], y); });
    };
    for (const std::uint32_t x : common)
        if (!triangle_with(v, w, x)) {
            ++counters_.topology;
            return false;
        }
    // The edges vx and wx of a common neighbour x become one: no tissue may have more than two triangles on
    // it (two junction edges fused, or a thin layer pinched along an edge, would make its surface touch itself).
    for (const std::uint32_t x : common) {
        std::vector<std::pair<Label, int>>& uses = edit_.uses;
        uses.clear();
        for (const std::uint32_t a : {v, w})
            for (const std::uint32_t t : stars_[a]) {
                const Triangle& tri = triangles_[t];
                if (!has(tri, x) || (has(tri, v) && has(tri, w))) continue;
                for (const Label label : {sides_[t].from, sides_[t].to}) {
                    auto it = std::find_if(uses.begin(), uses.end(), [&](const auto& u) { return u.first == label; });
                    if (it == uses.end()) uses.emplace_back(label, 1);
                    else if (++it->second > 2) {
                        ++counters_.topology;
                        return false;
                    }
                }
            }
    }
    for (std::size_t i = 0; i < common.size(); ++i)
        for (std::size_t j = i + 1; j < common.size(); ++j)
            if (triangle_with(v, common[i], common[j]) && triangle_with(w, common[i], common[j])) {
                ++counters_.topology;
                return false;
            }
    // The new triangles: the star of v with w for v; those on vw die.
    std::vector<std::uint32_t>& changed = edit_.changed;
    std::vector<std::uint32_t>& dying = edit_.dying;
    changed.clear();
    dying.clear();
    for (const std::uint32_t t : stars_[v]) (has(triangles_[t], w) ? dying : changed).push_back(t);
    for (const std::uint32_t t : changed) {
        Triangle now = triangles_[t];
        for (std::uint32_t& x : now)
            if (x == v) x = w;
        if (!shape_ok(now, triangles_[t], true)) return false;
        if (limits_.max_edge_mm > 0)
            for (const std::uint32_t x : now)
                if (x != w && distance(positions_[x], positions_[w]) > limits_.max_edge_mm &&
                    edge_multiplicity(w, x) == 0) {
                    ++counters_.shape;
                    return false;
                }
    }
    if (!inside_fence(stars_[v])) {
        ++counters_.fence;
        return false;
    }
    if (veto && !veto()) return false;
    // Apply, judge, and undo when refused.
    keep_prior();
    std::vector<SmallPiece>& pieces_before = edit_.pieces_before;
    std::vector<SmallPiece>& pieces_at_w = edit_.pieces_at_w;
    // The tissues of the dying triangles are one piece at v and at w: looked at once, from v. When every piece
    // at v and w has more than 24 triangles beyond the dying ones, more than 24 remain joined at w.
    std::array<Label, 8> dying_tissues{};
    std::size_t dying_count = 0;
    for (const std::uint32_t t : dying)
        for (const Label tissue : {sides_[t].from, sides_[t].to})
            if (dying_count < dying_tissues.size() &&
                std::find(dying_tissues.begin(), dying_tissues.begin() + dying_count, tissue) ==
                    dying_tissues.begin() + dying_count)
                dying_tissues[dying_count++] = tissue;
    bool pieces_clear = small_pieces(v, pieces_before, dying.size());
    // w's own pieces count too: the collapse may thin a piece at w alone
    pieces_clear =
        small_pieces(w, pieces_at_w, dying.size(), std::span(dying_tissues.data(), dying_count)) && pieces_clear;
    for (const SmallPiece& p : pieces_at_w)
        if (std::none_of(pieces_before.begin(), pieces_before.end(),
                         [&](const SmallPiece& b) { return b.tissue == p.tissue; }))
            pieces_before.push_back(p);
    const auto apply = [&] {
        begin_edit();
        save_star(v);
        save_star(w);
        for (const std::uint32_t t : dying)
            for (const std::uint32_t x : triangles_[t])
                if (x != v && x != w) save_star(x);
        for (const std::uint32_t t : dying) {
            save(t);
            alive_[t] = 0;
            recount(t, -1);
            for (const std::uint32_t x : triangles_[t])
                if (x != v) remove_from_star(x, t);
        }
        for (const std::uint32_t t : changed) {
            save(t);
            for (std::uint32_t& x : triangles_[t])
                if (x == v) x = w;
            stars_[w].push_back(t);
        }
        stars_[v].clear();
    };
    apply();
    // The sectors before the collapse only when those after fall under the limit: undone, measured, made again.
    const auto sectors_before = [&] {
        undo();
        const double before = std::min(smallest_sector_deg(stars_[v]), smallest_sector_deg(stars_[w]));
        apply();
        return before;
    };
    if (!judge_merge(w, sectors_before, pieces_clear)) return false;
    reclassify(w, &common);
    kinds_[v] = VertexKind::corner;
    ++counters_.accepted;
    return true;
}

bool LocalEditor::try_contract(const std::vector<std::uint32_t>& cluster, std::uint32_t r,
                               const std::function<bool()>& veto)
{
    if (cluster.size() < 2 || std::find(cluster.begin(), cluster.end(), r) == cluster.end()) return false;
    const auto in_cluster = [&](std::uint32_t x) {
        return std::find(cluster.begin(), cluster.end(), x) != cluster.end();
    };
    for (const std::uint32_t c : cluster)
        if (!vertex_alive(c) || kinds_[c] != VertexKind::patch) {
            ++counters_.topology;
            return false;
        }
    // The disc: the triangles around the cluster, all of one patch. A triangle with one cluster vertex holds an
    // edge of the rim (its other two, in its own order); the others die.
    std::vector<std::uint32_t>& changed = edit_.changed;
    std::vector<std::uint32_t>& dying = edit_.dying;
    std::vector<std::uint32_t>& rim = edit_.rim; // pairs: the rim edge of changed[i] is rim[2i] -> rim[2i + 1]
    changed.clear(), dying.clear(), rim.clear();
    const LabelPair side = sides_[stars_[r].front()];
    std::size_t disc = 0;
    for (const std::uint32_t c : cluster)
        for (const std::uint32_t t : stars_[c]) {
            const Triangle& tri = triangles_[t];
            int inside = 0, first = -1;
            for (int k = 0; k < 3; ++k)
                if (in_cluster(tri[k])) {
                    if (first < 0) first = k;
                    ++inside;
                }
            if (tri[first] != c) continue; // each triangle once: from its first cluster vertex
            if (!(sides_[t] == side)) {
                ++counters_.topology;
                return false;
            }
            ++disc;
            if (inside > 1) {
                dying.push_back(t);
                continue;
            }
            changed.push_back(t);
            rim.push_back(tri[(first + 1) % 3]);
            rim.push_back(tri[(first + 2) % 3]);
        }
    // One simple cycle of at least 4 rim edges, each with a triangle beyond it (a junction edge may have more: the
    // fans' order and the sector rule judge those), and a disc's count of triangles (Euler: 2 per cluster vertex,
    // plus one per rim edge, less 2): anything else is no disc.
    const std::size_t m = changed.size();
    if (m < 4 || disc != m + 2 * cluster.size() - 2) {
        ++counters_.topology;
        return false;
    }
    for (std::size_t i = 0; i < m; ++i) {
        if (edge_multiplicity(rim[2 * i], rim[2 * i + 1]) < 2) {
            ++counters_.topology;
            return false;
        }
        for (std::size_t j = 0; j < i; ++j)
            if (rim[2 * i] == rim[2 * j] || rim[2 * i + 1] == rim[2 * j + 1]) {
                ++counters_.topology;
                return false;
            }
    }
    std::size_t walked = 1;
    for (std::uint32_t at = rim[1]; at != rim[0]; ++walked) {
        std::size_t i = 0;
        while (i < m && rim[2 * i] != at) ++i;
        if (i == m || walked > m) {
            ++counters_.topology;
            return false;
        }
        at = rim[2 * i + 1];
    }
    if (walked != m) {
        ++counters_.topology;
        return false;
    }
    // Each new triangle against the one it replaces, as for a collapse; new edges no longer than the bound.
    for (std::size_t i = 0; i < m; ++i) {
        const std::uint32_t t = changed[i];
        Triangle now = triangles_[t];
        for (std::uint32_t& x : now)
            if (in_cluster(x)) x = r;
        if (!shape_ok(now, triangles_[t], true)) return false;
        if (limits_.max_edge_mm > 0)
            for (const std::uint32_t x : {rim[2 * i], rim[2 * i + 1]})
                if (distance(positions_[x], positions_[r]) > limits_.max_edge_mm && edge_multiplicity(r, x) == 0) {
                    ++counters_.shape;
                    return false;
                }
    }
    for (const std::uint32_t c : cluster)
        if (!inside_fence(stars_[c])) {
            ++counters_.fence;
            return false;
        }
    if (veto && !veto()) return false;
    keep_prior();
    // Every triangle of the disc lies in one piece per tissue (the patch's two), which r's triangles stay joined in.
    std::vector<SmallPiece>& pieces_before = edit_.pieces_before;
    const bool pieces_clear = small_pieces(r, pieces_before, dying.size());
    const auto apply = [&] {
        begin_edit();
        for (const std::uint32_t c : cluster) save_star(c);
        for (const std::uint32_t x : rim) save_star(x);
        for (const std::uint32_t t : dying) {
            save(t);
            alive_[t] = 0;
            recount(t, -1);
            for (const std::uint32_t x : triangles_[t])
                if (!in_cluster(x)) remove_from_star(x, t);
        }
        for (const std::uint32_t t : changed) {
            save(t);
            for (std::uint32_t& x : triangles_[t])
                if (in_cluster(x)) x = r;
        }
        for (const std::uint32_t c : cluster) stars_[c].clear();
        stars_[r] = changed;
    };
    apply();
    const auto sectors_before = [&] {
        undo();
        double before = 360;
        for (const std::uint32_t c : cluster) before = std::min(before, smallest_sector_deg(stars_[c]));
        apply();
        return before;
    };
    if (!judge_merge(r, sectors_before, pieces_clear)) return false;
    reclassify(r);
    for (const std::uint32_t c : cluster)
        if (c != r) kinds_[c] = VertexKind::corner;
    ++counters_.accepted;
    return true;
}

std::optional<std::uint32_t> LocalEditor::try_split(std::uint32_t v, std::uint32_t w, const Vec3& p)
{
    if (v == w || !vertex_alive(v) || !vertex_alive(w)) return std::nullopt;
    std::vector<std::uint32_t>& parents = edit_.parents;
    parents.clear();
    for (const std::uint32_t t : stars_[v])
        if (has(triangles_[t], w)) parents.push_back(t);
    if (parents.size() < 2) return std::nullopt;
    const double sectors_before = smallest_sector_deg(parents); // the parents' triangles change: measured now
    begin_edit();
    if (positions_.size() >= std::numeric_limits<std::uint32_t>::max() - 1)
        throw InputError("LocalEditor: over 2^32 vertices");
    const auto u = static_cast<std::uint32_t>(positions_.size());
    positions_.push_back(p);
    stars_.emplace_back();
    kinds_.push_back(parents.size() >= 3 ? VertexKind::curve : VertexKind::patch);
    reclassified_.clear();
    save_star(w);
    for (const std::uint32_t t : parents)
        for (const std::uint32_t x : triangles_[t])
            if (x != v && x != w) save_star(x);
    std::vector<std::uint32_t>& changed = edit_.changed;
    changed.clear();
    std::vector<Prior>& before = edit_.prior;
    before.clear();
    bool shape = true;
    for (const std::uint32_t t : parents) {
        save(t);
        const Triangle parent = triangles_[t];
        Triangle near_v = parent, near_w = parent;
        for (int k = 0; k < 3; ++k) {
            if (parent[k] == w) near_v[k] = u;
            if (parent[k] == v) near_w[k] = u;
        }
        shape = shape && shape_ok(near_v, parent, true) && shape_ok(near_w, parent, true);
        triangles_[t] = near_v;
        remove_from_star(w, t);
        stars_[u].push_back(t);
        const std::uint32_t added = new_triangle(near_w, sides_[t]);
        piece_of_[added] = piece_of_[t];
        recount(added, 1);
        changed.push_back(t);
        changed.push_back(added);
        before.emplace_back(t, corners(parent));
        before.emplace_back(added, corners(parent));
    }
    if (!shape || !inside_fence(changed)) {
        if (shape) ++counters_.fence;
        undo();
        return std::nullopt;
    }
    if (!sectors_ok(changed, [&] { return sectors_before; }) || !surroundings_ok(changed, before)) {
        undo();
        return std::nullopt;
    }
    for (const std::uint32_t t : changed) {
        if (t < triangles_before_edit_) unfile(t);
        file(t);
    }
    alive_count_ += parents.size();
    reclassify(u);
    ++counters_.accepted;
    return u;
}

bool LocalEditor::try_flip(std::uint32_t v, std::uint32_t w)
{
    if (v == w || !vertex_alive(v)) return false;
    std::uint32_t first = 0, second = 0;
    int found = 0;
    for (const std::uint32_t t : stars_[v])
        if (has(triangles_[t], w)) (found++ == 0 ? first : second) = t;
    if (found != 2 || !(sides_[first] == sides_[second])) return false;
    // first runs v -> w, second w -> v (one patch, consistently oriented).
    const auto runs = [&](std::uint32_t t, std::uint32_t a, std::uint32_t b) {
        const Triangle& x = triangles_[t];
        for (int k = 0; k < 3; ++k)
            if (x[k] == a && x[(k + 1) % 3] == b) return true;
        return false;
    };
    if (!runs(first, v, w)) std::swap(first, second);
    if (!runs(first, v, w) || !runs(second, w, v)) return false;
    const auto apex = [&](std::uint32_t t) {
        for (const std::uint32_t x : triangles_[t])
            if (x != v && x != w) return x;
        return v;
    };
    const std::uint32_t a = apex(first), b = apex(second);
    if (a == b || edge_multiplicity(a, b) != 0) {
        ++counters_.topology;
        return false;
    }
    if (limits_.max_edge_mm > 0 && distance(positions_[a], positions_[b]) > limits_.max_edge_mm &&
        distance(positions_[a], positions_[b]) > distance(positions_[v], positions_[w])) {
        ++counters_.shape;
        return false;
    }
    const Triangle one{a, v, b}, two{b, w, a};
    // The pair against the pair it replaces: not degenerate, no smaller angle than the limit unless no
    // smaller than the old pair's smallest, and each new normal within the tilt limit of the old pair's
    // (area-weighted: a flat cap being flipped away has no normal of its own worth comparing with).
    {
        const TriangleCorners o1 = corners(triangles_[first]), o2 = corners(triangles_[second]);
        const TriangleCorners n1 = corners(one), n2 = corners(two);
        const Vec3 old_normal = cross(o1[1] - o1[0], o1[2] - o1[0]) + cross(o2[1] - o2[0], o2[2] - o2[0]);
        const double old_cos = std::max(smallest_angle_cosine(o1), smallest_angle_cosine(o2));
        for (const TriangleCorners& n : {n1, n2}) {
            const Vec3 normal = cross(n[1] - n[0], n[2] - n[0]);
            const double scale =
                std::max({dot(n[1] - n[0], n[1] - n[0]), dot(n[2] - n[0], n[2] - n[0]), dot(n[2] - n[1], n[2] - n[1])});
            if (!(dot(normal, normal) > 1e-20 * scale * scale)) {
                ++counters_.shape;
                return false;
            }
            if (dot(normal, old_normal) < cos_max_tilt_ * norm(normal) * norm(old_normal)) {
                ++counters_.normal;
                return false;
            }
            const double cosine = smallest_angle_cosine(n);
            if (cosine > cos_min_angle_ && cosine > old_cos) {
                ++counters_.shape;
                return false;
            }
        }
    }
    std::vector<std::uint32_t>& changed = edit_.changed;
    changed.assign({first, second});
    if (!inside_fence(changed)) {
        ++counters_.fence;
        return false;
    }
    const double sectors_before = smallest_sector_deg(changed);
    begin_edit();
    for (const std::uint32_t x : {v, w, a, b}) save_star(x);
    std::vector<Prior>& prior = edit_.prior;
    prior.assign({{first, corners(triangles_[first])}, {second, corners(triangles_[second])}});
    save(first);
    save(second);
    triangles_[first] = one;
    triangles_[second] = two;
    remove_from_star(v, second);
    remove_from_star(w, first);
    stars_[a].push_back(second);
    stars_[b].push_back(first);
    if (!sectors_ok(changed, [&] { return sectors_before; }) || !surroundings_ok(changed, prior)) {
        undo();
        return false;
    }
    for (const std::uint32_t t : changed) {
        unfile(t);
        file(t);
    }
    for (const std::uint32_t x : {v, w, a, b}) kinds_[x] = classify(x);
    ++counters_.accepted;
    return true;
}

bool LocalEditor::try_move(std::uint32_t v, const Vec3& p)
{
    if (!vertex_alive(v)) return false;
    if (!inside_fence(stars_[v])) {
        ++counters_.fence;
        return false;
    }
    begin_edit();
    std::vector<Prior>& before = edit_.prior;
    before.clear();
    for (const std::uint32_t t : stars_[v]) before.emplace_back(t, corners(triangles_[t]));
    const Vec3 old = positions_[v];
    positions_[v] = p;
    for (const auto& [t, was] : before) {
        const TriangleCorners now = corners(triangles_[t]);
        const Vec3 na = cross(now[1] - now[0], now[2] - now[0]), nb = cross(was[1] - was[0], was[2] - was[0]);
        const double scale = std::max({dot(now[1] - now[0], now[1] - now[0]), dot(now[2] - now[0], now[2] - now[0]),
                                       dot(now[2] - now[1], now[2] - now[1])});
        bool ok = dot(na, na) > 1e-20 * scale * scale;
        if (ok && dot(na, nb) < cos_max_tilt_ * norm(na) * norm(nb)) ++counters_.normal, ok = false;
        if (ok) {
            const double cosine = smallest_angle_cosine(now);
            if (cosine > cos_min_angle_ && cosine > smallest_angle_cosine(was)) ++counters_.shape, ok = false;
        }
        if (!ok) {
            positions_[v] = old;
            return false;
        }
    }
    if (!inside_fence(stars_[v])) {
        ++counters_.fence;
        positions_[v] = old;
        return false;
    }
    const auto sectors_before = [&] { // only when the sectors after the move fall under the limit
        positions_[v] = old;
        const double sectors = smallest_sector_deg(stars_[v]);
        positions_[v] = p;
        return sectors;
    };
    if (!sectors_ok(stars_[v], sectors_before) || !surroundings_ok(stars_[v], before)) {
        positions_[v] = old;
        return false;
    }
    if (path_crosses(v, old, p)) {
        ++counters_.intersection;
        positions_[v] = old;
        return false;
    }
    std::vector<SmallPiece>& pieces_before = edit_.pieces_before;
    std::vector<SmallPiece>& pieces_after = edit_.pieces_after;
    small_pieces(v, pieces_after);
    positions_[v] = old;
    small_pieces(v, pieces_before);
    if (!pieces_ok(pieces_before, pieces_after)) {
        ++counters_.topology;
        return false;
    }
    positions_[v] = p;
    for (const std::uint32_t t : stars_[v]) {
        unfile(t);
        file(t);
    }
    ++counters_.accepted;
    return true;
}

InterfaceComplex LocalEditor::result() const
{
    InterfaceComplex out;
    out.names = names_;
    out.background = background_;
    std::vector<std::uint32_t> index(positions_.size(), std::numeric_limits<std::uint32_t>::max());
    for (std::uint32_t t = 0; t < triangles_.size(); ++t) {
        if (!alive_[t]) continue;
        Triangle tri = triangles_[t];
        for (std::uint32_t& v : tri) {
            if (index[v] == std::numeric_limits<std::uint32_t>::max()) {
                index[v] = static_cast<std::uint32_t>(out.vertices.size());
                out.vertices.push_back(positions_[v]);
            }
            v = index[v];
        }
        out.add_triangle(tri, sides_[t]);
    }
    return out;
}

} // namespace tissuemesh::surface::detail

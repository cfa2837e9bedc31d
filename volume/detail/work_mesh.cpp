#include "volume/detail/work_mesh.h"

#include <algorithm>
#include <limits>

#include "core/error.h"
#include "core/tet_adjacency.h"
#include "volume/detail/face_map.h"

namespace tissuemesh::volume::detail {
namespace {

void erase_value(std::vector<std::uint32_t>& list, std::uint32_t value)
{
    const auto found = std::find(list.begin(), list.end(), value);
    if (found == list.end()) return;
    *found = list.back();
    list.pop_back();
}

bool holds(const Tet& tet, std::uint32_t v) { return tet[0] == v || tet[1] == v || tet[2] == v || tet[3] == v; }
bool holds(const Triangle& tri, std::uint32_t v) { return tri[0] == v || tri[1] == v || tri[2] == v; }

/// Whether the order (a, b, c, d) of tet's nodes is an even permutation of its stored order.
bool even_order(const Tet& tet, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d)
{
    const std::uint32_t wanted[4] = {a, b, c, d};
    int position[4];
    for (int i = 0; i < 4; ++i)
        position[i] = static_cast<int>(std::find(tet.begin(), tet.end(), wanted[i]) - tet.begin());
    int inversions = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) inversions += position[i] > position[j];
    return inversions % 2 == 0;
}

} // namespace

WorkMesh::WorkMesh(const TetMesh& mesh, std::vector<char> frozen)
    : points_(mesh.vertices), kinds_(mesh.vertices.size(), NodeKind::interior), frozen_(std::move(frozen)),
      tets_of_(mesh.vertices.size()), faces_of_(mesh.vertices.size()), tets_(mesh.tets), labels_(mesh.tet_labels),
      alive_(mesh.tets.size(), 1), quality_(mesh.tets.size()), volume_(mesh.tets.size(), 0),
      stamps_(mesh.tets.size(), 0), births_(mesh.tets.size(), 0), alive_count_(mesh.tets.size()), names_(mesh.names)
{
    // Built directly, not through the journaled edits: nothing here is ever undone.
    std::vector<std::uint32_t> degree(points_.size(), 0);
    for (const Tet& tet : tets_)
        for (const std::uint32_t v : tet) ++degree[v];
    for (std::size_t v = 0; v < points_.size(); ++v) tets_of_[v].reserve(degree[v]);
    scales_.assign(points_.size(), std::numeric_limits<double>::infinity());
    // The qualities side by side (each tet's alone: the same values whatever the threads).
    const auto count = static_cast<std::int64_t>(tets_.size());
#pragma omp parallel for schedule(static)
    for (std::int64_t t = 0; t < count; ++t)
        quality_[static_cast<std::size_t>(t)] = min_sine(corners(static_cast<std::uint32_t>(t)));
    for (std::uint32_t t = 0; t < tets_.size(); ++t) {
        link_tet(t);
        for (const auto& e : edge_corners) {
            const std::uint32_t a = tets_[t][e[0]], b = tets_[t][e[1]];
            const double length = distance(points_[a], points_[b]);
            scales_[a] = std::min(scales_[a], length), scales_[b] = std::min(scales_[b], length);
        }
    }
    faces_.reserve(mesh.faces.size() + 64);
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
        if (!face_with(mesh.faces[f][0], mesh.faces[f][1], mesh.faces[f][2]))
            add_face(mesh.faces[f], mesh.face_sides[f], true);
    // Faces the tissues or the outer boundary imply but the list lacks are kept all the same: every face of the
    // tets once (core's face adjacency, ascending by nodes), each of its tets in increasing order.
    const TetAdjacency adjacency(tets_, points_.size());
    const auto keep_face = [&](const TetAdjacency::Face& face) {
        if (face.holders > 2)
            throw InputError(concat("mesh: a face of tetrahedron ", face.tets[0], " is shared by ", face.holders,
                                    " tetrahedra; the mesh is not conforming (run tm-check-mesh)"));
        const bool boundary = face.holders == 1;
        for (std::uint32_t j = 0; j < face.holders; ++j) {
            const std::uint32_t t = face.tets[j], other = boundary ? t : face.tets[1 - j];
            if (!boundary && labels_[other] == labels_[t]) break;
            const auto& key = face.vertices;
            if (const auto listed = face_with(key[0], key[1], key[2])) {
                if (boundary) outer_at_start_.push_back(*listed);
                break;
            }
            if (boundary) outer_at_start_.push_back(static_cast<std::uint32_t>(faces_.size()));
            // Outward from t: the face opposite its corner (the node not on the face) turned away from it.
            const Tet& tet = tets_[t];
            const auto corner = static_cast<std::size_t>(
                std::find_if(tet.begin(), tet.end(),
                             [&](std::uint32_t v) { return std::find(key.begin(), key.end(), v) == key.end(); }) -
                tet.begin());
            const auto& local = local_faces[corner];
            add_face({tet[local[0]], tet[local[2]], tet[local[1]]}, {labels_[t], boundary ? Label{0} : labels_[other]},
                     false);
        }
    };
    for (std::uint32_t v = 0; v < adjacency.vertex_count(); ++v) adjacency.for_each_face_at(v, keep_face);
    for (std::uint32_t v = 0; v < points_.size(); ++v) kinds_[v] = compute_kind(v);
    std::sort(outer_at_start_.begin(), outer_at_start_.end());
    journal_.clear();
}

TetMesh WorkMesh::result() const
{
    TetMesh mesh;
    mesh.vertices = points_;
    mesh.names = names_;
    for (std::size_t t = 0; t < tets_.size(); ++t)
        if (alive_[t]) mesh.tets.push_back(tets_[t]), mesh.tet_labels.push_back(labels_[t]);
    for (const ConstraintFace& f : faces_)
        if (f.alive && f.listed) mesh.faces.push_back(f.corners), mesh.face_sides.push_back(f.sides);
    return mesh;
}

std::vector<Label> WorkMesh::tissues_at(std::uint32_t v) const
{
    std::vector<Label> tissues;
    for (const std::uint32_t f : faces_of_[v])
        tissues.push_back(faces_[f].sides.from), tissues.push_back(faces_[f].sides.to);
    std::sort(tissues.begin(), tissues.end());
    tissues.erase(std::unique(tissues.begin(), tissues.end()), tissues.end());
    return tissues;
}

std::vector<std::uint32_t> WorkMesh::curve_neighbours(std::uint32_t v) const
{
    std::vector<std::uint32_t> ends;
    for (const std::uint32_t f : faces_of_[v])
        for (const std::uint32_t w : faces_[f].corners)
            if (w != v && std::find(ends.begin(), ends.end(), w) == ends.end()) ends.push_back(w);
    std::vector<std::uint32_t> junction;
    for (const std::uint32_t w : ends) {
        int count = 0;
        for (const std::uint32_t f : faces_of_[v]) count += holds(faces_[f].corners, w);
        if (count >= 3) junction.push_back(w);
    }
    return junction;
}

NodeKind WorkMesh::compute_kind(std::uint32_t v) const
{
    if (frozen(v)) return NodeKind::corner;
    const auto& star = faces_of_[v];
    if (star.empty()) return NodeKind::interior;
    std::vector<std::pair<std::uint32_t, int>> ring; // neighbour, faces on the edge to it
    for (const std::uint32_t f : star)
        for (const std::uint32_t w : faces_[f].corners) {
            if (w == v) continue;
            auto found = std::find_if(ring.begin(), ring.end(), [&](const auto& e) { return e.first == w; });
            if (found == ring.end()) ring.push_back({w, 1});
            else ++found->second;
        }
    int junction = 0;
    for (const auto& [w, count] : ring) {
        if (count >= 3) ++junction;
        else if (count != 2) return NodeKind::corner;
    }
    if (junction == 2) return NodeKind::curve;
    if (junction != 0) return NodeKind::corner;
    const auto pair = std::minmax(faces_[star.front()].sides.from, faces_[star.front()].sides.to);
    for (const std::uint32_t f : star)
        if (std::minmax(faces_[f].sides.from, faces_[f].sides.to) != pair) return NodeKind::corner;
    // One fan around v has as many neighbours as faces; two fans touching at v share none.
    return ring.size() == star.size() ? NodeKind::surface : NodeKind::corner;
}

TetCorners WorkMesh::corners(std::uint32_t t) const { return corners(tets_[t]); }

TetCorners WorkMesh::corners(const Tet& tet) const
{
    return {points_[tet[0]], points_[tet[1]], points_[tet[2]], points_[tet[3]]};
}

std::optional<std::uint32_t> WorkMesh::face_with(std::uint32_t a, std::uint32_t b, std::uint32_t c) const
{
    // The faces at a node are few (none at an inner node): a scan beats a hash lookup, a cache miss in a big map.
    const auto& list = faces_of_[a].size() <= faces_of_[b].size() ? faces_of_[a] : faces_of_[b];
    const std::uint32_t other = faces_of_[a].size() <= faces_of_[b].size() ? b : a;
    for (const std::uint32_t f : list) {
        const Triangle& corners = faces_[f].corners;
        if (holds(corners, other) && holds(corners, c)) return f;
    }
    return std::nullopt;
}

bool WorkMesh::constrained_edge(std::uint32_t a, std::uint32_t b) const
{
    return std::any_of(faces_of_[a].begin(), faces_of_[a].end(),
                       [&](std::uint32_t f) { return holds(faces_[f].corners, b); });
}

bool WorkMesh::has_edge(std::uint32_t a, std::uint32_t b) const
{
    const auto& list = tets_of_[a].size() <= tets_of_[b].size() ? tets_of_[a] : tets_of_[b];
    const std::uint32_t other = tets_of_[a].size() <= tets_of_[b].size() ? b : a;
    return std::any_of(list.begin(), list.end(), [&](std::uint32_t t) { return holds(tets_[t], other); });
}

void WorkMesh::tets_of_edge(std::uint32_t a, std::uint32_t b, std::vector<std::uint32_t>& out) const
{
    out.clear();
    for (const std::uint32_t t : tets_of_[a])
        if (holds(tets_[t], b)) out.push_back(t);
}

std::optional<std::uint32_t> WorkMesh::tet_with(std::uint32_t a, std::uint32_t b, std::uint32_t c,
                                                std::uint32_t d) const
{
    for (const std::uint32_t t : tets_of_[a])
        if (holds(tets_[t], b) && holds(tets_[t], c) && holds(tets_[t], d)) return t;
    return std::nullopt;
}

std::optional<std::uint32_t> WorkMesh::tet_across(std::uint32_t t, int i) const
{
    const Tet& tet = tets_[t];
    const std::uint32_t a = tet[(i + 1) % 4], b = tet[(i + 2) % 4], c = tet[(i + 3) % 4];
    for (const std::uint32_t u : tets_of_[a])
        if (u != t && holds(tets_[u], b) && holds(tets_[u], c)) return u;
    return std::nullopt;
}

bool WorkMesh::edge_ring(std::uint32_t a, std::uint32_t b, std::vector<std::uint32_t>& ring,
                         std::vector<std::uint32_t>& tets, bool* open) const
{
    std::vector<std::uint32_t> around;
    tets_of_edge(a, b, around);
    // Each tet (a, b, c, d) positively oriented joins c to d in the ring.
    std::vector<std::array<std::uint32_t, 3>> links; // from, to, tet
    for (const std::uint32_t t : around) {
        std::uint32_t other[2], n = 0;
        for (const std::uint32_t v : tets_[t])
            if (v != a && v != b) other[n++] = v;
        if (!even_order(tets_[t], a, b, other[0], other[1])) std::swap(other[0], other[1]);
        links.push_back({other[0], other[1], t});
    }
    ring.clear(), tets.clear();
    if (links.empty()) return false;
    // An open chain starts where no link ends.
    std::uint32_t start = links[0][0];
    bool chain = false;
    for (const auto& l : links)
        if (std::none_of(links.begin(), links.end(), [&](const auto& m) { return m[1] == l[0]; }))
            start = l[0], chain = true;
    if (chain && open == nullptr) return false;
    if (!chain && links.size() < 3) return false;
    std::uint32_t at = start;
    for (std::size_t step = 0; step < links.size(); ++step) {
        const auto next = std::find_if(links.begin(), links.end(), [&](const auto& l) { return l[0] == at; });
        if (next == links.end()) return false;
        ring.push_back(at), tets.push_back((*next)[2]);
        at = (*next)[1];
    }
    if (open != nullptr) *open = chain;
    if (chain) ring.push_back(at);
    else if (at != start) return false;
    // Every node once: a walk that came back onto itself early is no ring.
    std::vector<std::uint32_t> sorted = ring;
    std::sort(sorted.begin(), sorted.end());
    return std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end();
}

std::uint32_t WorkMesh::add_tet(const Tet& tet, Label label)
{
    std::uint32_t t;
    if (!free_slots_.empty()) {
        t = free_slots_.back();
        free_slots_.pop_back();
        tets_[t] = tet, labels_[t] = label, alive_[t] = 1, ++births_[t];
    } else {
        t = static_cast<std::uint32_t>(tets_.size());
        tets_.push_back(tet), labels_.push_back(label), alive_.push_back(1), quality_.push_back(0),
            volume_.push_back(0), stamps_.push_back(0), births_.push_back(0);
    }
    link_tet(t);
    ++alive_count_;
    refresh_quality(t);
    journal_.push_back({Change::tet_added, t});
    return t;
}

void WorkMesh::remove_tet(std::uint32_t t)
{
    alive_[t] = 0;
    unlink_tet(t);
    --alive_count_;
    ++stamps_[t];
    freed_now_.push_back(t);
    journal_.push_back({Change::tet_removed, t, {}, NodeKind::interior, births_[t]});
}

void WorkMesh::move_node(std::uint32_t v, const Vec3& p)
{
    journal_.push_back({Change::node_moved, v, points_[v]});
    points_[v] = p;
    for (const std::uint32_t t : tets_of_[v]) refresh_quality(t);
}

std::uint32_t WorkMesh::add_node(const Vec3& p)
{
    const auto v = static_cast<std::uint32_t>(points_.size());
    points_.push_back(p), kinds_.push_back(NodeKind::interior), tets_of_.emplace_back(), faces_of_.emplace_back();
    scales_.push_back(std::numeric_limits<double>::infinity());
    journal_.push_back({Change::node_added, v});
    return v;
}

std::uint32_t WorkMesh::add_face(const Triangle& corners, LabelPair sides, bool listed)
{
    const auto f = static_cast<std::uint32_t>(faces_.size());
    faces_.push_back({corners, sides, listed, true});
    link_face(f);
    journal_.push_back({Change::face_added, f});
    return f;
}

void WorkMesh::remove_face(std::uint32_t f)
{
    faces_[f].alive = false;
    unlink_face(f);
    journal_.push_back({Change::face_removed, f});
}

void WorkMesh::classify(std::uint32_t v)
{
    const NodeKind kind = compute_kind(v);
    if (kind == kinds_[v]) return;
    journal_.push_back({Change::kind_set, v, {}, kinds_[v]});
    kinds_[v] = kind;
}

void WorkMesh::rollback(std::size_t mark)
{
    while (journal_.size() > mark) {
        const Entry e = journal_.back();
        journal_.pop_back();
        switch (e.change) {
        case Change::tet_added:
            alive_[e.index] = 0, unlink_tet(e.index), --alive_count_, ++stamps_[e.index];
            free_slots_.push_back(e.index);
            break;
        case Change::tet_removed:
            alive_[e.index] = 1, link_tet(e.index), ++alive_count_, refresh_quality(e.index),
            births_[e.index] = e.birth;
            freed_now_.pop_back(); // the newest freed slot is this one: the journal unwinds in order
            break;
        case Change::node_moved:
            points_[e.index] = e.point;
            for (const std::uint32_t t : tets_of_[e.index]) refresh_quality(t);
            break;
        case Change::node_added:
            points_.pop_back(), kinds_.pop_back(), tets_of_.pop_back(), faces_of_.pop_back(), scales_.pop_back();
            break;
        case Change::face_added: unlink_face(e.index), faces_.pop_back(); break;
        case Change::face_removed: faces_[e.index].alive = true, link_face(e.index); break;
        case Change::kind_set: kinds_[e.index] = e.kind; break;
        }
    }
}

void WorkMesh::commit()
{
    journal_.clear();
    free_slots_.insert(free_slots_.end(), freed_now_.begin(), freed_now_.end());
    freed_now_.clear();
}

std::vector<std::uint32_t> WorkMesh::take_touched()
{
    std::vector<std::uint32_t> touched;
    touched.swap(touched_);
    return touched;
}

void WorkMesh::swept_faces(std::size_t mark, std::vector<std::array<Vec3, 3>>& before,
                           std::vector<std::array<Vec3, 3>>& after) const
{
    before.clear(), after.clear();
    // Nodes moved since mark with where they were then (the first entry of each), faces added and removed.
    std::vector<std::pair<std::uint32_t, Vec3>> moved;
    std::vector<std::uint32_t> added, removed, at_moved;
    auto new_nodes_from = static_cast<std::uint32_t>(points_.size());
    for (std::size_t i = mark; i < journal_.size(); ++i) {
        const Entry& e = journal_[i];
        switch (e.change) {
        case Change::node_added: new_nodes_from = std::min(new_nodes_from, e.index); break;
        case Change::node_moved: moved.emplace_back(e.index, e.point); break;
        case Change::face_added: added.push_back(e.index); break;
        case Change::face_removed: removed.push_back(e.index); break;
        default: break;
        }
    }
    // Faces added since mark did not exist then: their ids are not in `before`, whatever happened to them.
    std::sort(added.begin(), added.end());
    const auto is_added = [&](std::uint32_t f) { return std::binary_search(added.begin(), added.end(), f); };
    std::stable_sort(moved.begin(), moved.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    moved.erase(
        std::unique(moved.begin(), moved.end(), [](const auto& a, const auto& b) { return a.first == b.first; }),
        moved.end());
    for (const auto& [v, from] : moved) {
        if (v >= new_nodes_from) continue;
        at_moved.insert(at_moved.end(), faces_of_[v].begin(), faces_of_[v].end());
    }
    std::sort(at_moved.begin(), at_moved.end());
    at_moved.erase(std::unique(at_moved.begin(), at_moved.end()), at_moved.end());
    const auto then = [&](std::uint32_t v) -> const Vec3& {
        const auto it = std::lower_bound(moved.begin(), moved.end(), v,
                                         [](const auto& entry, std::uint32_t node) { return entry.first < node; });
        return it != moved.end() && it->first == v ? it->second : points_[v];
    };
    const auto corners_then = [&](std::uint32_t f) {
        const Triangle& c = faces_[f].corners;
        return std::array<Vec3, 3>{then(c[0]), then(c[1]), then(c[2])};
    };
    const auto corners_now = [&](std::uint32_t f) {
        const Triangle& c = faces_[f].corners;
        return std::array<Vec3, 3>{points_[c[0]], points_[c[1]], points_[c[2]]};
    };
    for (const std::uint32_t f : removed)
        if (!is_added(f)) before.push_back(corners_then(f));
    for (const std::uint32_t f : added)
        if (faces_[f].alive) after.push_back(corners_now(f));
    for (const std::uint32_t f : at_moved)
        if (!is_added(f)) before.push_back(corners_then(f)), after.push_back(corners_now(f)); // added: in `after`
}

void WorkMesh::faces_changed_since(std::size_t mark, std::vector<std::uint32_t>& out) const
{
    out.clear();
    for (std::size_t i = mark; i < journal_.size(); ++i) {
        const Entry& e = journal_[i];
        if (e.change == Change::face_added) out.push_back(e.index);
        if (e.change == Change::node_moved) out.insert(out.end(), faces_of_[e.index].begin(), faces_of_[e.index].end());
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    out.erase(std::remove_if(out.begin(), out.end(), [&](std::uint32_t f) { return !faces_[f].alive; }), out.end());
}

int WorkMesh::holders(std::uint32_t a, std::uint32_t b, std::uint32_t c) const
{
    int count = 0;
    for (const std::uint32_t t : tets_of_[a]) count += alive_[t] && holds(tets_[t], b) && holds(tets_[t], c);
    return count;
}

WorkMesh::Balance WorkMesh::balance_since(std::size_t mark) const
{
    Balance balance{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    std::vector<std::uint32_t> added;
    for (std::size_t e = mark; e < journal_.size(); ++e) {
        const Entry& entry = journal_[e];
        if (entry.change == Change::tet_added) added.push_back(entry.index);
        if (entry.change == Change::tet_removed && std::find(added.begin(), added.end(), entry.index) == added.end())
            balance.before = std::min(balance.before, quality_[entry.index]);
        if (entry.change == Change::node_moved && entry.index < points_.size())
            for (const std::uint32_t t : tets_of_[entry.index]) balance.after = std::min(balance.after, quality_[t]);
    }
    for (const std::uint32_t t : added)
        if (alive_[t]) balance.after = std::min(balance.after, quality_[t]);
    return balance;
}

void WorkMesh::link_tet(std::uint32_t t)
{
    for (const std::uint32_t v : tets_[t]) tets_of_[v].push_back(t);
    const TetCorners c = corners(t);
    volume_[t] = dot(c[1] - c[0], cross(c[2] - c[0], c[3] - c[0])) / 6;
    tissue_volumes_[labels_[t]] += volume_[t];
}

void WorkMesh::unlink_tet(std::uint32_t t)
{
    for (const std::uint32_t v : tets_[t]) erase_value(tets_of_[v], t);
    tissue_volumes_[labels_[t]] -= volume_[t];
}

void WorkMesh::link_face(std::uint32_t f)
{
    const Triangle& c = faces_[f].corners;
    for (const std::uint32_t v : c) faces_of_[v].push_back(f);
}

void WorkMesh::unlink_face(std::uint32_t f)
{
    const Triangle& c = faces_[f].corners;
    for (const std::uint32_t v : c) erase_value(faces_of_[v], f);
}

void WorkMesh::refresh_quality(std::uint32_t t)
{
    const TetCorners c = corners(t);
    if (alive_[t]) {
        const double volume = dot(c[1] - c[0], cross(c[2] - c[0], c[3] - c[0])) / 6;
        tissue_volumes_[labels_[t]] += volume - volume_[t];
        volume_[t] = volume;
    }
    quality_[t] = min_sine(c);
    ++stamps_[t];
    touched_.push_back(t);
}

} // namespace tissuemesh::volume::detail

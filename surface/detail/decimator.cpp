#include "surface/detail/decimator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace tissuemesh::surface::detail {

Carried initial_carried(const InterfaceComplex& complex)
{
    Carried carried{std::vector<Quadric>(complex.vertices.size()),
                    std::vector<std::vector<std::uint32_t>>(complex.triangles.size())};
    constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> first(complex.vertices.size(), none);
    for (std::uint32_t t = 0; t < complex.triangles.size(); ++t) {
        const Triangle& tri = complex.triangles[t];
        for (const std::uint32_t v : tri)
            if (first[v] == none) first[v] = t;
        const TriangleCorners c{complex.vertices[tri[0]], complex.vertices[tri[1]], complex.vertices[tri[2]]};
        const Vec3 n = cross(c[1] - c[0], c[2] - c[0]);
        const double area2 = norm(n);
        if (area2 <= 0) continue;
        const Vec3 u = (1.0 / area2) * n; // the plane's sign does not matter to its quadric
        Quadric plane(u[0], u[1], u[2], -dot(u, c[0]));
        plane *= 0.5 * area2; // area-weighted
        for (const std::uint32_t v : tri) carried.quadrics[v] += plane;
    }
    for (std::uint32_t v = 0; v < complex.vertices.size(); ++v)
        if (first[v] != none) carried.samples[first[v]].push_back(v);
    return carried;
}

void add_counters(DecimateReport& report, const EditCounters& counters)
{
    report.refused_topology += counters.topology;
    report.refused_shape += counters.shape;
    report.refused_fold += counters.normal;
    report.refused_intersection += counters.intersection;
    report.refused_gap += counters.gap;
    report.refused_wedge += counters.wedge;
}

Decimator::Decimator(InterfaceComplex&& complex, Carried&& carried, double cell_mm, const DecimateOptions& options,
                     const LayerSizing& sizing, DecimateReport& report, std::optional<Slab> slab)
    : options_(options), sizing_(sizing), report_(report), editor_(std::move(complex), limits_of(options), cell_mm),
      quadrics_(std::move(carried.quadrics)), samples_(std::move(carried.samples)), slab_(slab)
{
    if (slab) editor_.set_fence(slab->fence(options.min_gap_mm));
}

template <class Visit>
void Decimator::for_each_target(std::uint32_t v, Visit visit) const
{
    if (!editor_.vertex_alive(v) || editor_.kind(v) == VertexKind::corner) return;
    const bool curve = editor_.kind(v) == VertexKind::curve;
    editor_.ring(v, ring_);
    for (const LocalEditor::RingEntry& e : ring_) {
        if (curve && e.triangles < 3) continue;
        if (const std::optional<double> c = cost(v, e.vertex)) visit(*c, e.vertex);
    }
}

void Decimator::collapse_all(const Progress& progress, const std::vector<std::uint32_t>* seeds)
{
    if (seeds) {
        for (const std::uint32_t v : *seeds) enqueue(v);
    } else {
        for (std::uint32_t v = 0; v < editor_.vertex_slots(); ++v) enqueue(v);
    }
    const std::size_t start = editor_.triangle_count();
    std::size_t next_rebuild = start / 2;
    while (!queue_.empty()) {
        if (options_.target_triangles > 0 && editor_.triangle_count() <= options_.target_triangles) break;
        const VertexQueue::Entry c = queue_.top();
        queue_.pop();
        if (!editor_.vertex_alive(c.v)) continue;
        const std::optional<std::uint32_t> w = collapse_cheapest(c.v);
        if (!w) continue;
        ++report_.collapses;
        enqueue(*w);
        editor_.ring(*w, around_);
        for (const LocalEditor::RingEntry& e : around_) requeue_neighbour(e.vertex, c.v, *w, e.triangles);
        if (editor_.triangle_count() < next_rebuild) {
            editor_.rebuild_grid(2 * editor_.mean_edge_length());
            next_rebuild = editor_.triangle_count() / 2;
            progress.update("decimate",
                            1.0 - static_cast<double>(editor_.triangle_count()) / static_cast<double>(start));
        }
    }
}

void Decimator::contract_blocks(const Vec3& origin)
{
    const double block = options_.contract_block_mm;
    struct Item {
        std::array<std::int64_t, 3> cube;
        LabelPair side;
        std::uint32_t v;
        auto key() const { return std::tuple(cube, side.from, side.to); }
    };
    std::vector<Item> items;
    for (std::uint32_t v = 0; v < editor_.vertex_slots(); ++v) {
        if (!editor_.vertex_alive(v) || editor_.kind(v) != VertexKind::patch) continue;
        Item item{{}, editor_.side(editor_.star(v).front()), v};
        for (int a = 0; a < 3; ++a)
            item.cube[a] = static_cast<std::int64_t>(std::floor((editor_.position(v)[a] - origin[a]) / block));
        items.push_back(item);
    }
    std::sort(items.begin(), items.end(),
              [](const Item& a, const Item& b) { return std::tuple(a.key(), a.v) < std::tuple(b.key(), b.v); });
    std::vector<std::uint32_t> group, cluster;
    std::vector<char> taken;
    for (std::size_t i = 0; i < items.size();) {
        std::size_t j = i;
        group.clear();
        while (j < items.size() && items[j].key() == items[i].key()) group.push_back(items[j++].v);
        i = j;
        if (group.size() < 2) continue;
        // The group's pieces joined by edges, each from its lowest vertex.
        taken.assign(group.size(), 0);
        for (std::size_t seed = 0; seed < group.size(); ++seed) {
            if (taken[seed]) continue;
            taken[seed] = 1;
            cluster.assign(1, group[seed]);
            for (std::size_t n = 0; n < cluster.size(); ++n) {
                editor_.ring(cluster[n], ring_);
                for (const LocalEditor::RingEntry& e : ring_) {
                    const auto it = std::lower_bound(group.begin(), group.end(), e.vertex);
                    if (it == group.end() || *it != e.vertex) continue;
                    const std::size_t k = static_cast<std::size_t>(it - group.begin());
                    if (!taken[k]) taken[k] = 1, cluster.push_back(e.vertex);
                }
            }
            if (cluster.size() < 2) continue;
            std::sort(cluster.begin(), cluster.end());
            // The members in the order of the quadric error of the collapses into them (where the cluster's planes
            // meet best first): the first that passes is kept.
            Quadric q = quadrics_[cluster.front()];
            for (std::size_t n = 1; n < cluster.size(); ++n) q += quadrics_[cluster[n]];
            std::vector<std::pair<double, std::uint32_t>>& order = enqueue_scratch_;
            order.clear();
            for (const std::uint32_t c : cluster) {
                const Vec3& p = editor_.position(c);
                order.emplace_back(q(OpenMesh::Vec3d(p[0], p[1], p[2])), c);
            }
            std::sort(order.begin(), order.end());
            const bool done = std::any_of(order.begin(), order.end(), [&](const std::pair<double, std::uint32_t>& o) {
                return contract(cluster, o.second);
            });
            if (done) {
                ++report_.contractions;
                report_.contracted_vertices += cluster.size() - 1;
            } else {
                ++report_.contractions_refused;
            }
        }
    }
}

bool Decimator::contract(const std::vector<std::uint32_t>& cluster, std::uint32_t r)
{
    std::vector<std::uint32_t>& targets = targets_;
    std::vector<std::uint32_t>& sources = sources_;
    std::vector<std::pair<std::size_t, std::uint32_t>>& assignment = assignment_;
    std::vector<TriangleCorners>& shapes = shapes_;
    targets.clear(), sources.clear(), assignment.clear(), shapes.clear();
    const auto in_cluster = [&](std::uint32_t x) { return std::binary_search(cluster.begin(), cluster.end(), x); };
    double worst = 0;
    const Vec3& at = editor_.position(r);
    // Asked by the editor once the disc is known to be one: the new edges and the distance bound.
    const auto within_bounds = [&] {
        for (const std::uint32_t t : editor_.pending_changed()) {
            sources.push_back(t);
            const Triangle& tri = editor_.triangle(t);
            const auto k = static_cast<std::size_t>(std::find_if(tri.begin(), tri.end(), in_cluster) - tri.begin());
            const Vec3& from = editor_.position(tri[k]);
            TriangleCorners corners = editor_.corners(t);
            corners[k] = at;
            // A new edge from r no longer than the bounds, or than the edge from the cluster vertex it replaces.
            if (options_.max_edge_mm > 0)
                for (const std::size_t o : {(k + 1) % 3, (k + 2) % 3}) {
                    const Vec3& x = editor_.position(tri[o]);
                    const double length = distance(at, x);
                    if (length <= distance(from, x)) continue;
                    if (length > options_.max_edge_mm ||
                        (options_.edge_per_thickness > 0 && length > 4.0 / 3.0 * sizing_.at(0.5 * (at + x))))
                        return false;
                }
            targets.push_back(t);
            shapes.push_back(corners);
        }
        const std::vector<std::uint32_t>& dying = editor_.pending_dying();
        sources.insert(sources.end(), dying.begin(), dying.end());
        // Half the distance bound: a contraction spends the budget wherever its block lies, where the cheapest-first
        // collapses would spend it where the surface is flattest (with the whole bound the one-voxel layers of the
        // 2 mm sphere head and the thin shell lost 0.003-0.004 of their Dice; with half, none).
        return assign_samples(sources, shapes, assignment, worst, 0.5 * options_.max_distance_mm);
    };
    if (!editor_.try_contract(cluster, r, within_bounds)) return false;
    for (const std::uint32_t t : sources) samples_[t].clear();
    for (const auto& [i, s] : assignment) samples_[targets[i]].push_back(s);
    for (const std::uint32_t c : cluster)
        if (c != r) quadrics_[r] += quadrics_[c];
    report_.max_distance_mm = std::max(report_.max_distance_mm, worst);
    return true;
}

void Decimator::split_long_edges()
{
    std::vector<std::pair<double, std::pair<std::uint32_t, std::uint32_t>>> edges;
    for (std::uint32_t t = 0; t < editor_.triangle_slots(); ++t) {
        if (!editor_.triangle_alive(t)) continue;
        const Triangle& tri = editor_.triangle(t);
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = std::min(tri[k], tri[(k + 1) % 3]), b = std::max(tri[k], tri[(k + 1) % 3]);
            const double length = distance(editor_.position(a), editor_.position(b));
            if (length > 4.0 / 3.0 * target_edge(a, b)) edges.push_back({-length, {a, b}});
        }
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (const auto& [length, edge] : edges) {
        const auto [a, b] = edge;
        if (editor_.edge_multiplicity(a, b) == 0) continue;
        const std::optional<std::uint32_t> m =
            editor_.try_split(a, b, 0.5 * (editor_.position(a) + editor_.position(b)));
        if (!m) continue;
        ++report_.splits;
        redistribute_samples(*m);
    }
}

void Decimator::hand_over(const std::vector<std::uint32_t>& from_vertex, Piece& piece) const
{
    const Slab& slab = *slab_;
    for (std::uint32_t t = 0; t < editor_.triangle_slots(); ++t) {
        if (!editor_.triangle_alive(t)) continue;
        const TriangleCorners c = editor_.corners(t);
        if (!slab.owns(std::min({c[0][slab.axis], c[1][slab.axis], c[2][slab.axis]}))) continue;
        Triangle tri = editor_.triangle(t);
        for (std::uint32_t& v : tri) v = from_vertex[v];
        piece.triangles.push_back(tri);
        piece.sides.push_back(editor_.side(t));
        std::vector<std::uint32_t>& samples = piece.samples.emplace_back();
        for (const std::uint32_t s : samples_[t]) samples.push_back(from_vertex[s]);
    }
    for (std::uint32_t v = 0; v < editor_.vertex_slots(); ++v)
        if (editor_.vertex_alive(v) && slab.owns(editor_.position(v)[slab.axis]))
            piece.quadrics.emplace_back(from_vertex[v], quadrics_[v]);
    for (const std::uint32_t v : fenced_)
        if (editor_.vertex_alive(v)) piece.fenced.push_back(from_vertex[v]);
    add_counters(piece.report, editor_.counters());
}

double Decimator::target_edge(std::uint32_t a, std::uint32_t b) const
{
    double target = options_.target_edge_mm > 0 ? options_.target_edge_mm : std::numeric_limits<double>::max();
    if (options_.target_edge_mm_by_pair.empty()) return target;
    double by_pair = std::numeric_limits<double>::max();
    for (const std::uint32_t t : editor_.star(a)) {
        const Triangle& tri = editor_.triangle(t);
        if (std::find(tri.begin(), tri.end(), b) == tri.end()) continue;
        const LabelPair& side = editor_.side(t);
        for (const auto& key : {std::pair{side.from, side.to}, std::pair{side.to, side.from}})
            if (const auto it = options_.target_edge_mm_by_pair.find(key); it != options_.target_edge_mm_by_pair.end())
                by_pair = std::min(by_pair, it->second);
    }
    return by_pair < std::numeric_limits<double>::max() ? by_pair : target;
}

std::optional<double> Decimator::cost(std::uint32_t v, std::uint32_t w) const
{
    const Vec3& p = editor_.position(w);
    if (options_.mode == DecimateMode::size) {
        const double length = distance(editor_.position(v), p), target = target_edge(v, w);
        if (length >= 0.8 * target) return std::nullopt;
        return length / target;
    }
    Quadric q = quadrics_[v];
    q += quadrics_[w];
    return q(OpenMesh::Vec3d(p[0], p[1], p[2]));
}

std::vector<std::pair<double, std::uint32_t>> Decimator::targets_of(std::uint32_t v) const
{
    std::vector<std::pair<double, std::uint32_t>> targets;
    for_each_target(v, [&](double c, std::uint32_t w) { targets.emplace_back(c, w); });
    std::sort(targets.begin(), targets.end());
    return targets;
}

void Decimator::enqueue(std::uint32_t v)
{
    std::vector<std::pair<double, std::uint32_t>>& targets = enqueue_scratch_;
    targets.clear();
    for_each_target(v, [&](double c, std::uint32_t w) { targets.emplace_back(c, w); });
    std::sort(targets.begin(), targets.end());
    const bool bounded = options_.mode == DecimateMode::curvature && options_.max_edge_mm > 0;
    for (const auto& [c, w] : targets) {
        if (bounded && !short_enough(v, w)) { // ring_ still holds v's ring
            ++report_.refused_by_length;
            continue;
        }
        queue_.set({c, v, w});
        return;
    }
    queue_.erase(v);
}

void Decimator::requeue_neighbour(std::uint32_t u, std::uint32_t v, std::uint32_t w, std::uint32_t multiplicity)
{
    const VertexQueue::Entry* old = queue_.find(u);
    const std::vector<std::uint32_t>& changed = editor_.reclassified();
    if (old == nullptr || old->w == v || old->w == w || std::find(changed.begin(), changed.end(), u) != changed.end()) {
        enqueue(u);
        return;
    }
    const VertexKind kind = editor_.kind(u);
    if (kind == VertexKind::corner || (kind == VertexKind::curve && multiplicity < 3)) return;
    const std::optional<double> c = cost(u, w);
    if (!c || !(std::pair{*c, w} < std::pair{old->cost, old->w})) return;
    if (options_.mode == DecimateMode::curvature && options_.max_edge_mm > 0 && !keeps_edges_short(u, w)) return;
    queue_.set({*c, u, w});
}

std::optional<std::uint32_t> Decimator::collapse_cheapest(std::uint32_t v)
{
    for (const auto& [c, w] : targets_of(v))
        if (collapse(v, w)) return w;
    return std::nullopt;
}

bool Decimator::assign_samples(const std::vector<std::uint32_t>& sources, const std::vector<TriangleCorners>& shapes,
                               std::vector<std::pair<std::size_t, std::uint32_t>>& assignment, double& worst,
                               double bound) const
{
    std::vector<std::pair<Vec3, double>>& spheres = spheres_;
    spheres.clear();
    for (const TriangleCorners& c : shapes) {
        const Vec3 centre = (1.0 / 3.0) * (c[0] + c[1] + c[2]);
        spheres.emplace_back(centre,
                             std::max({distance(c[0], centre), distance(c[1], centre), distance(c[2], centre)}));
    }
    for (const std::uint32_t t : sources)
        for (const std::uint32_t s : samples_[t]) {
            const Vec3& p = editor_.position(s);
            std::size_t nearest = 0;
            double best = std::numeric_limits<double>::max();
            for (std::size_t i = 0; i < shapes.size(); ++i) {
                if (distance(p, spheres[i].first) - spheres[i].second >= best) continue;
                const double d = distance(p, closest_point_on_triangle(p, shapes[i]));
                if (d < best) best = d, nearest = i;
            }
            if (best > bound) return false;
            worst = std::max(worst, best);
            assignment.emplace_back(nearest, s);
        }
    return true;
}

bool Decimator::collapse(std::uint32_t v, std::uint32_t w)
{
    if (slab_ && !(editor_.inside_fence(editor_.star(v)) && editor_.inside_fence(editor_.star(w)))) {
        fenced_.push_back(v);
        return false;
    }
    if (options_.mode == DecimateMode::curvature && options_.max_edge_mm > 0 && !keeps_edges_short(v, w)) {
        ++report_.refused_by_length;
        return false;
    }
    // Scratch kept between calls: collapses are tried millions of times.
    std::vector<std::uint32_t>& targets = targets_;
    std::vector<std::uint32_t>& sources = sources_;
    std::vector<std::pair<std::size_t, std::uint32_t>>& assignment = assignment_;
    std::vector<TriangleCorners>& shapes = shapes_;
    targets.clear(), sources.clear(), assignment.clear(), shapes.clear();
    double worst = 0;
    bool too_far = false;
    const auto within_bound = [&] {
        for (const std::uint32_t t : editor_.star(v)) {
            sources.push_back(t);
            const Triangle& tri = editor_.triangle(t);
            if (std::find(tri.begin(), tri.end(), w) != tri.end()) continue;
            TriangleCorners c = editor_.corners(t);
            for (int k = 0; k < 3; ++k)
                if (tri[k] == v) c[k] = editor_.position(w);
            targets.push_back(t);
            shapes.push_back(c);
        }
        for (const std::uint32_t t : editor_.star(w)) {
            const Triangle& tri = editor_.triangle(t);
            if (std::find(tri.begin(), tri.end(), v) != tri.end()) continue;
            targets.push_back(t);
            shapes.push_back(editor_.corners(t));
        }
        // Every input vertex the changed triangles answer for must stay within the bound.
        too_far = !assign_samples(sources, shapes, assignment, worst, options_.max_distance_mm);
        return !too_far;
    };
    if (!editor_.try_collapse(v, w, within_bound)) {
        ++(too_far ? report_.refused_by_distance : report_.refused_by_checks);
        return false;
    }
    for (const std::uint32_t t : sources) samples_[t].clear();
    for (const auto& [i, s] : assignment) samples_[targets[i]].push_back(s);
    quadrics_[w] += quadrics_[v];
    report_.max_distance_mm = std::max(report_.max_distance_mm, worst);
    return true;
}

bool Decimator::keeps_edges_short(std::uint32_t v, std::uint32_t w) const
{
    editor_.ring(v, ring_);
    return short_enough(v, w);
}

bool Decimator::short_enough(std::uint32_t v, std::uint32_t w) const
{
    const Vec3& p = editor_.position(w);
    for (const LocalEditor::RingEntry& e : ring_) {
        const Vec3& q = editor_.position(e.vertex);
        const double length = distance(p, q);
        if (e.vertex == w || length <= distance(editor_.position(v), q) || editor_.edge_multiplicity(w, e.vertex) != 0)
            continue;
        if (length > options_.max_edge_mm) return false;
        if (options_.edge_per_thickness > 0 && length > 4.0 / 3.0 * sizing_.at(0.5 * (p + q))) return false;
    }
    return true;
}

void Decimator::redistribute_samples(std::uint32_t m)
{
    if (samples_.size() < editor_.triangle_slots()) samples_.resize(editor_.triangle_slots());
    if (quadrics_.size() < editor_.vertex_slots()) quadrics_.resize(editor_.vertex_slots());
    std::vector<std::uint32_t> pool;
    const std::vector<std::uint32_t>& star = editor_.star(m);
    for (const std::uint32_t t : star) {
        pool.insert(pool.end(), samples_[t].begin(), samples_[t].end());
        samples_[t].clear();
    }
    for (const std::uint32_t s : pool) {
        const Vec3& p = editor_.position(s);
        std::uint32_t nearest = star.front();
        double best = std::numeric_limits<double>::max();
        for (const std::uint32_t t : star) {
            const double d = distance(p, closest_point_on_triangle(p, editor_.corners(t)));
            if (d < best) best = d, nearest = t;
        }
        samples_[nearest].push_back(s);
    }
}

} // namespace tissuemesh::surface::detail

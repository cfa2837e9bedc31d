#include "volume/detail/surface_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "surface/detail/triangle_distance.h"

namespace tissuemesh::volume::detail {
namespace {

using surface::detail::Box3;

std::uint32_t pair_key(Label a, Label b)
{
    const auto [low, high] = std::minmax(a, b);
    return static_cast<std::uint32_t>(low) << 16 | high;
}

double box_distance(const Vec3& p, const Box3& box)
{
    double sum = 0;
    for (int i = 0; i < 3; ++i) {
        const double d = std::max({0.0, box.low[i] - p[i], p[i] - box.high[i]});
        sum += d * d;
    }
    return std::sqrt(sum);
}

} // namespace

SurfaceReference::SurfaceReference(const InterfaceComplex& complex)
    : SurfaceReference(complex.vertices, complex.triangles, complex.sides)
{
}

SurfaceReference::SurfaceReference(std::vector<Vec3> vertices, std::vector<Triangle> triangles,
                                   const std::vector<LabelPair>& sides)
    : vertices_(std::move(vertices)), triangles_(std::move(triangles))
{
    std::vector<surface::detail::CompactBox> boxes(triangles_.size());
    std::vector<std::uint32_t> ids(triangles_.size());
    // Edges with the tissues of the triangles on them, in a sorted list (deterministic, no hashing).
    std::vector<std::pair<std::array<std::uint32_t, 2>, std::uint32_t>> edges; // edge, triangle
    double edge_sum = 0;
    for (std::uint32_t t = 0; t < triangles_.size(); ++t) {
        const Triangle& tri = triangles_[t];
        pairs_.push_back(pair_key(sides[t].from, sides[t].to));
        boxes[t] = surface::detail::compact(
            surface::detail::bounding_box({vertices_[tri[0]], vertices_[tri[1]], vertices_[tri[2]]}));
        ids[t] = t;
        for (int k = 0; k < 3; ++k) {
            const auto [a, b] = std::minmax(tri[k], tri[(k + 1) % 3]);
            edges.push_back({{a, b}, t});
            edge_sum += distance(vertices_[a], vertices_[b]);
        }
    }
    if (!edges.empty()) mean_edge_mm_ = edge_sum / static_cast<double>(edges.size());
    triangle_index_ = surface::detail::BoxIndex(boxes, ids);
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        std::vector<Label> tissues;
        for (; j < edges.size() && edges[j].first == edges[i].first; ++j) {
            const std::uint32_t t = edges[j].second;
            tissues.push_back(sides[t].from), tissues.push_back(sides[t].to);
        }
        if (j - i >= 3) {
            std::sort(tissues.begin(), tissues.end());
            tissues.erase(std::unique(tissues.begin(), tissues.end()), tissues.end());
            const auto set =
                tissue_sets_.emplace(tissues, static_cast<std::uint32_t>(tissue_sets_.size())).first->second;
            segments_.push_back(edges[i].first);
            segment_tissues_.push_back(set);
        }
        i = j;
    }
    boxes.resize(segments_.size());
    ids.resize(segments_.size());
    for (std::uint32_t s = 0; s < segments_.size(); ++s) {
        const Vec3& a = vertices_[segments_[s][0]];
        boxes[s] = surface::detail::compact(surface::detail::bounding_box({a, a, vertices_[segments_[s][1]]}));
        ids[s] = s;
    }
    segment_index_ = surface::detail::BoxIndex(boxes, ids);
}

template <class Closest>
std::optional<Vec3> SurfaceReference::nearest(const surface::detail::BoxIndex& index, std::size_t items, const Vec3& p,
                                              double reach, Closest closest, std::uint32_t* hint) const
{
    std::optional<Vec3> best;
    double best_distance = std::numeric_limits<double>::max();
    std::uint32_t best_item = std::numeric_limits<std::uint32_t>::max();
    // The search box grows from a quarter of a typical edge until it holds the nearest point found (nothing
    // outside it can be nearer) or reaches `reach`; from the hint's distance at once when the hint is that near.
    double r = std::min(reach, 0.25 * mean_edge_mm_);
    if (hint != nullptr && *hint < items)
        if (const std::optional<Vec3> q = closest(*hint, best_distance); q && distance(p, *q) <= reach)
            best = q, best_distance = distance(p, *q), best_item = *hint, r = best_distance;
    for (;; r = std::min(reach, 2 * r)) {
        index.visit(Box3{p - Vec3{r, r, r}, p + Vec3{r, r, r}}, [&](std::uint32_t i) {
            const std::optional<Vec3> q = closest(i, best_distance);
            if (!q) return;
            const double d = distance(p, *q);
            if (d < best_distance || (d == best_distance && i < best_item)) best_distance = d, best = *q, best_item = i;
        });
        if (best_distance <= r) {
            if (hint != nullptr) *hint = best_item;
            return best;
        }
        if (r >= reach) return std::nullopt;
    }
}

std::optional<Vec3> SurfaceReference::onto_patch(const Vec3& p, Label a, Label b, double reach,
                                                 std::uint32_t* hint) const
{
    const std::uint32_t key = pair_key(a, b);
    return nearest(
        triangle_index_, triangles_.size(), p, reach,
        [&](std::uint32_t t, double so_far) -> std::optional<Vec3> {
            if (pairs_[t] != key) return std::nullopt;
            const Triangle& tri = triangles_[t];
            const surface::detail::TriangleCorners c{vertices_[tri[0]], vertices_[tri[1]], vertices_[tri[2]]};
            if (box_distance(p, surface::detail::bounding_box(c)) > so_far) return std::nullopt;
            return surface::detail::closest_point_on_triangle(p, c);
        },
        hint);
}

std::optional<Vec3> SurfaceReference::onto_curve(const Vec3& p, const std::vector<Label>& tissues, double reach) const
{
    const auto set = tissue_sets_.find(tissues);
    if (set == tissue_sets_.end()) return std::nullopt;
    return nearest(segment_index_, segments_.size(), p, reach, [&](std::uint32_t s, double) -> std::optional<Vec3> {
        if (segment_tissues_[s] != set->second) return std::nullopt;
        return surface::detail::closest_point_on_segment(p, vertices_[segments_[s][0]], vertices_[segments_[s][1]]);
    });
}

double SurfaceReference::distance_to(const Vec3& p, Label a, Label b, bool any_pair, double reach) const
{
    const std::uint32_t key = pair_key(a, b);
    const std::optional<Vec3> q = nearest(
        triangle_index_, triangles_.size(), p, reach, [&](std::uint32_t t, double so_far) -> std::optional<Vec3> {
            if (!any_pair && pairs_[t] != key) return std::nullopt;
            const Triangle& tri = triangles_[t];
            const surface::detail::TriangleCorners c{vertices_[tri[0]], vertices_[tri[1]], vertices_[tri[2]]};
            if (box_distance(p, surface::detail::bounding_box(c)) > so_far) return std::nullopt;
            return surface::detail::closest_point_on_triangle(p, c);
        });
    return q ? distance(p, *q) : std::numeric_limits<double>::infinity();
}

bool SurfaceReference::triangle_within(std::uint32_t t, const Vec3& p, double tolerance) const
{
    const Triangle& tri = triangles_[t];
    const Vec3 d =
        p - surface::detail::closest_point_on_triangle(p, {vertices_[tri[0]], vertices_[tri[1]], vertices_[tri[2]]});
    return dot(d, d) <= tolerance * tolerance;
}

bool SurfaceReference::within(const Vec3& p, Label a, Label b, double tolerance, std::uint32_t* hint) const
{
    const std::uint32_t key = pair_key(a, b);
    if (hint != nullptr && *hint < triangles_.size() && pairs_[*hint] == key && triangle_within(*hint, p, tolerance))
        return true;
    bool found = false;
    // Any triangle of the pair that near will do: the visit stops at the first.
    triangle_index_.visit(Box3{p - Vec3{tolerance, tolerance, tolerance}, p + Vec3{tolerance, tolerance, tolerance}},
                          [&](std::uint32_t t) {
                              found = pairs_[t] == key && triangle_within(t, p, tolerance);
                              if (found && hint != nullptr) *hint = t;
                              return found;
                          });
    return found;
}

bool SurfaceReference::holds_triangle(const Vec3& a, const Vec3& b, const Vec3& c, Label from, Label to,
                                      double tolerance) const
{
    // The centroid first: it is the farthest from the corners, which lie on the patch.
    for (const Vec3& p : {(1.0 / 3) * (a + b + c), 0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a)})
        if (!within(p, from, to, tolerance)) return false;
    return true;
}

} // namespace tissuemesh::volume::detail

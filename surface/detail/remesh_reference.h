// Reference: the input surface of remesh(), for projecting vertices back onto it: its triangles by tissue
// pair and its junction edges, each in a BoxIndex. Read-only once built, so the slabs of a remeshing share it.
// Included by remesh.cpp only.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "core/interface_complex.h"
#include "surface/detail/box_index.h"
#include "surface/detail/layer_sizing.h"
#include "surface/detail/triangle_distance.h"

namespace tissuemesh::surface::detail {

/// The tissue pair of a side, smaller label first.
inline std::pair<Label, Label> unordered(const LabelPair& side) { return std::minmax(side.from, side.to); }

/// Distance from p to the closed box (0 inside): a lower bound of the distance to anything in it.
inline double box_distance(const Vec3& p, const Box3& box)
{
    double sum = 0;
    for (int i = 0; i < 3; ++i) {
        const double d = std::max({0.0, box.low[i] - p[i], p[i] - box.high[i]});
        sum += d * d;
    }
    return std::sqrt(sum);
}

/// The input surface, for projecting vertices back: its triangles by tissue pair, and its junction edges.
class Reference {
public:
    /// `sizing`: the target edge lengths by layer thickness (size_at()), measured on `input`.
    Reference(const InterfaceComplex& input, double cell_mm, const LayerSizingOptions& sizing = {})
        : input_(input), cell_mm_(cell_mm), sizing_(input, input.background, sizing)
    {
        std::vector<CompactBox> boxes(input.triangle_count());
        std::map<std::pair<Label, Label>, std::vector<std::uint32_t>> by_pair;
        for (std::uint32_t t = 0; t < input.triangle_count(); ++t) {
            boxes[t] = compact(bounding_box(corners(t)));
            by_pair[unordered(input.sides[t])].push_back(t);
        }
        for (const auto& [pair, members] : by_pair) patches_.emplace(pair, BoxIndex(boxes, members));
        std::vector<std::uint32_t> ids;
        // Junction edges: those of three triangles or more, in edge order.
        std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
        edges.reserve(3 * input.triangles.size());
        for (const Triangle& t : input.triangles)
            for (int k = 0; k < 3; ++k) edges.push_back(std::minmax(t[k], t[(k + 1) % 3]));
        std::sort(edges.begin(), edges.end());
        for (std::size_t i = 0, j = 0; i < edges.size(); i = j) {
            while (j < edges.size() && edges[j] == edges[i]) ++j;
            if (j - i >= 3) junction_.push_back(edges[i]);
        }
        boxes.resize(junction_.size());
        ids.resize(junction_.size());
        for (std::uint32_t s = 0; s < junction_.size(); ++s) boxes[s] = compact(bounding_box(segment(s))), ids[s] = s;
        segments_ = BoxIndex(boxes, ids);
    }

    /// `q` with each coordinate the corners share exactly set to theirs. A point projected onto a triangle in an
    /// axis plane (surface nets put many vertices on the planes of their cubes' margins) is otherwise off it by
    /// rounding, 1e-15 mm, and neighbours that should be coplanar are only nearly so. A guard: on the 1 mm usc19-5
    /// head it made no measured difference (its flat tets came from flattened small pieces, local_edits.cpp).
    static Vec3 on_shared_planes(Vec3 q, const TriangleCorners& c)
    {
        for (int a = 0; a < 3; ++a)
            if (c[0][a] == c[1][a] && c[0][a] == c[2][a]) q[a] = c[0][a];
        return q;
    }

    /// The nearest point of the input patch of `pair` to p (p itself when none is within reach); of equally
    /// near triangles, the first in the input's order.
    Vec3 onto_patch(const Vec3& p, std::pair<Label, Label> pair, double reach) const
    {
        const auto patch = patches_.find(pair);
        if (patch == patches_.end()) return p;
        return nearest(patch->second, p, reach, [&](std::uint32_t t, double nearest_so_far) -> std::optional<Vec3> {
            // The box is never further than the triangle: most candidates end here, at a fraction of the cost.
            const TriangleCorners c = corners(t);
            if (box_distance(p, bounding_box(c)) > nearest_so_far) return std::nullopt;
            return on_shared_planes(closest_point_on_triangle(p, c), c);
        });
    }

    /// The nearest point of the input junction curves to p (p itself when none is within reach); of equally
    /// near segments, the first in the input's order.
    Vec3 onto_curve(const Vec3& p, double reach) const
    {
        return nearest(segments_, p, reach, [&](std::uint32_t s, double nearest_so_far) -> std::optional<Vec3> {
            if (box_distance(p, bounding_box(segment(s))) > nearest_so_far) return std::nullopt;
            const Vec3 &a = input_.vertices[junction_[s].first], &b = input_.vertices[junction_[s].second];
            return on_shared_planes(closest_point_on_segment(p, a, b), {a, b, b});
        });
    }

private:
    TriangleCorners corners(std::uint32_t t) const
    {
        const Triangle& tri = input_.triangles[t];
        return {input_.vertices[tri[0]], input_.vertices[tri[1]], input_.vertices[tri[2]]};
    }
    TriangleCorners segment(std::uint32_t s) const
    {
        const Vec3& a = input_.vertices[junction_[s].first];
        return {a, a, input_.vertices[junction_[s].second]};
    }

    /// The nearest of the points closest(i, nearest so far) gives for the items of `index` whose boxes meet
    /// the box of half-width `reach` around p (p when none). The search box grows from a twentieth of a cell
    /// (most points asked lie a fraction of an edge from the surface: on the 1 mm usc19-5 head remeshing took
    /// 15.4 s starting from a quarter cell, 13.9 s from a twentieth) until it holds the nearest point found (then
    /// nothing outside it can be nearer) or reaches `reach`: the same answer as a search of the whole reach at
    /// once, at the cost of the few items near p.
    template <class Closest>
    Vec3 nearest(const BoxIndex& index, const Vec3& p, double reach, Closest closest) const
    {
        for (double r = std::min(reach, cell_mm_ / 20);; r = std::min(reach, 2 * r)) {
            Vec3 best = p;
            double best_distance = std::numeric_limits<double>::max();
            std::uint32_t best_item = std::numeric_limits<std::uint32_t>::max();
            index.visit(Box3{p - Vec3{r, r, r}, p + Vec3{r, r, r}}, [&](std::uint32_t i) {
                if (const std::optional<Vec3> q = closest(i, best_distance)) {
                    const double d = distance(p, *q);
                    if (d < best_distance || (d == best_distance && i < best_item))
                        best_distance = d, best = *q, best_item = i;
                }
            });
            if (best_distance <= r || r >= reach) return best;
        }
    }

public:
    /// The target edge length at p by the thickness of the input's layers there (LayerSizing).
    double size_at(const Vec3& p) const { return sizing_.at(p); }
    const LayerSizing& sizing() const { return sizing_; }

private:
    const InterfaceComplex& input_;
    double cell_mm_;
    LayerSizing sizing_;
    std::map<std::pair<Label, Label>, BoxIndex> patches_; ///< the input's triangles by their boxes, per tissue pair
    BoxIndex segments_;                                   ///< its junction edges by their boxes
    std::vector<std::pair<std::uint32_t, std::uint32_t>> junction_;
};

} // namespace tissuemesh::surface::detail

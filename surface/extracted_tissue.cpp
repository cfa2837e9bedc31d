#include "surface/extracted_tissue.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "surface/detail/extraction_labels.h"
#include "surface/detail/priority_cube.h"

namespace tissuemesh::surface {
namespace {

/// With 3-4 tissues in a tetrahedron the extracted surface is a fan from its centroid over the curves on its
/// faces, so a point has the tissue of the point where the ray from the centroid leaves the tetrahedron: the
/// weights become that face point's barycentric weights (the vertex with the smallest weight drops out).
/// With 2 tissues the surface is the plane of summed weight 1/2, left as it is.
void project_to_face_if_junction(const std::array<Label, 4>& label, std::array<double, 4>& weight)
{
    int distinct = 0;
    for (int c = 0; c < 4; ++c) distinct += std::find(label.begin(), label.begin() + c, label[c]) == label.begin() + c;
    const auto drop = static_cast<std::size_t>(std::min_element(weight.begin(), weight.end()) - weight.begin());
    if (distinct < 3 || weight[drop] >= 0.25) return; // two tissues, or the centroid itself
    const double scale = 0.25 / (0.25 - weight[drop]);
    for (double& w : weight) w = 0.25 + scale * (w - 0.25);
    weight[drop] = 0;
}

/// The side of the barycentric-dual surface a point with these weights is on (see ExtractedTissue).
Label dual_side(const std::array<Label, 4>& label, std::array<double, 4> weight)
{
    project_to_face_if_junction(label, weight);
    Label best = label[0];
    double best_weight = -1;
    for (int c = 0; c < 4; ++c) {
        double sum = 0;
        for (int d = 0; d < 4; ++d) sum += label[d] == label[c] ? weight[d] : 0.0;
        if (sum > best_weight || (sum == best_weight && label[c] < best)) best = label[c], best_weight = sum;
    }
    return best;
}

/// Cube vertex v (corner 0-7, centre 8) in the unit cube.
Vec3 vertex_position(int v)
{
    return v == 8 ? Vec3{0.5, 0.5, 0.5} : Vec3{double(v & 1), double(v >> 1 & 1), double(v >> 2 & 1)};
}

double orientation(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s)
{
    return dot(q - p, cross(r - p, s - p));
}

/// Barycentric weights of `u` in tetrahedron `tet` of the unit cube.
std::array<double, 4> barycentric(const detail::CubeTet& tet, const Vec3& u)
{
    std::array<Vec3, 4> p;
    for (int v = 0; v < 4; ++v) p[v] = vertex_position(tet[v]);
    const double whole = orientation(p[0], p[1], p[2], p[3]);
    std::array<double, 4> weight{};
    for (int v = 0; v < 4; ++v) {
        std::array<Vec3, 4> q = p;
        q[v] = u;
        weight[v] = orientation(q[0], q[1], q[2], q[3]) / whole;
    }
    return weight;
}

} // namespace

ExtractedTissue::ExtractedTissue(const LabelImage& image, const ExtractOptions& options)
    : image_(image), map_(detail::kept_label_map(options.tissues, options.background)), background_(options.background),
      rule_(options.priority.empty() ? nullptr : std::make_unique<const detail::PriorityRule>(options.priority))
{
}

ExtractedTissue::~ExtractedTissue() = default;
ExtractedTissue::ExtractedTissue(ExtractedTissue&&) noexcept = default;

Label ExtractedTissue::corner_label(const Index3& corner) const
{
    return image_.contains(corner)
               ? map_[image_.at(static_cast<std::size_t>(corner[0]), static_cast<std::size_t>(corner[1]),
                                static_cast<std::size_t>(corner[2]))]
               : background_;
}

Label ExtractedTissue::at_index(const Vec3& index) const
{
    Index3 base;
    Vec3 f;
    for (int axis = 0; axis < 3; ++axis)
        base[axis] = static_cast<std::int64_t>(std::floor(index[axis])),
        f[axis] = index[axis] - std::floor(index[axis]);
    if (rule_) {
        std::array<Label, 8> corners;
        for (int c = 0; c < 8; ++c)
            corners[c] = corner_label({base[0] + (c & 1), base[1] + (c >> 1 & 1), base[2] + (c >> 2 & 1)});
        const detail::CubePlan plan = rule_->plan(corners);
        if (plan.split) {
            // The split cube's tetrahedron holding f: the one whose smallest weight is largest (>= 0 inside it).
            const detail::CubeTets tets = detail::cube_tetrahedra(plan);
            std::array<double, 4> best_weight{};
            std::size_t best = 0;
            for (std::size_t t = 0; t < tets.count; ++t) {
                const std::array<double, 4> weight = barycentric(tets.tets[t], f);
                if (t == 0 || *std::min_element(weight.begin(), weight.end()) >
                                  *std::min_element(best_weight.begin(), best_weight.end()))
                    best = t, best_weight = weight;
            }
            std::array<Label, 4> label;
            for (int v = 0; v < 4; ++v) label[v] = tets.tets[best][v] == 8 ? plan.centre : corners[tets.tets[best][v]];
            return dual_side(label, best_weight);
        }
    }
    // The Kuhn tetrahedron holding f runs from corner 0 along the axes by decreasing fraction; its barycentric
    // weights are the differences of the sorted fractions.
    std::array<int, 3> order{0, 1, 2};
    std::sort(order.begin(), order.end(), [&](int a, int b) { return f[a] > f[b] || (f[a] == f[b] && a < b); });
    const std::array<double, 4> weight{1 - f[order[0]], f[order[0]] - f[order[1]], f[order[1]] - f[order[2]],
                                       f[order[2]]};
    std::array<Label, 4> label;
    Index3 corner = base;
    for (int c = 0; c < 4; ++c) {
        if (c > 0) ++corner[order[c - 1]];
        label[c] = corner_label(corner);
    }
    return dual_side(label, weight);
}

} // namespace tissuemesh::surface

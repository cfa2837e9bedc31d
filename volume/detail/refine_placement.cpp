#include "volume/detail/refine_placement.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tissuemesh::volume::detail {
namespace {

constexpr double min_weight = 0.05; // constrained mode: smallest barycentric weight of a new node
constexpr int bisections = 4;       // a quarter-voxel step bisected 4 times: 1/64 voxel

double tet_volume6(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
    return dot(b - a, cross(c - a, d - a));
}

/// Barycentric weights of `p` in the tet (they sum to 1; negative outside).
std::array<double, 4> barycentric(const std::array<Vec3, 4>& v, const Vec3& p)
{
    const double whole = tet_volume6(v[0], v[1], v[2], v[3]);
    if (whole == 0) return {0.25, 0.25, 0.25, 0.25};
    return {tet_volume6(p, v[1], v[2], v[3]) / whole, tet_volume6(v[0], p, v[2], v[3]) / whole,
            tet_volume6(v[0], v[1], p, v[3]) / whole, tet_volume6(v[0], v[1], v[2], p) / whole};
}

Vec3 centroid(const std::array<Vec3, 4>& v) { return 0.25 * (v[0] + v[1] + v[2] + v[3]); }

/// Centre of the inscribed sphere: the corners weighted by the areas of their opposite faces.
Vec3 incentre(const std::array<Vec3, 4>& v)
{
    Vec3 sum{0, 0, 0};
    double total = 0;
    for (int i = 0; i < 4; ++i) {
        const Vec3& a = v[(i + 1) % 4];
        const double area = norm(cross(v[(i + 2) % 4] - a, v[(i + 3) % 4] - a));
        sum = sum + area * v[i], total += area;
    }
    return total > 0 ? (1.0 / total) * sum : centroid(v);
}

Vec3 longest_edge_midpoint(const std::array<Vec3, 4>& v)
{
    Vec3 best = centroid(v);
    double longest = -1;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
            if (distance(v[i], v[j]) > longest) longest = distance(v[i], v[j]), best = 0.5 * (v[i] + v[j]);
    return best;
}

/// The first tissue change on the segment from `start` to `end` (sampled every `step_mm`, bisected), if any.
std::optional<Vec3> first_change(const LabelImage& image, const Vec3& start, const Vec3& end, double step_mm,
                                 Label background)
{
    const Label first = voxel_label_at(image, start, background);
    const double length = distance(start, end);
    const int steps = std::max(1, static_cast<int>(std::ceil(length / step_mm)));
    for (int k = 1; k <= steps; ++k) {
        double inside = static_cast<double>(k - 1) / steps, outside = static_cast<double>(k) / steps;
        if (voxel_label_at(image, start + outside * (end - start), background) == first) continue;
        for (int b = 0; b < bisections; ++b) {
            const double middle = 0.5 * (inside + outside);
            (voxel_label_at(image, start + middle * (end - start), background) == first ? inside : outside) = middle;
        }
        return start + (0.5 * (inside + outside)) * (end - start);
    }
    return std::nullopt;
}

/// Of the changes found along the strategy's rays, the one farthest from the tet's corners.
std::optional<Vec3> material_change(const LabelImage& image, const std::array<Vec3, 4>& v, Placement placement,
                                    Label background)
{
    const Vec3& spacing = image.spacing_mm();
    const double step_mm = 0.25 * std::min({spacing[0], spacing[1], spacing[2]});
    std::optional<Vec3> best;
    double best_clearance = -1;
    auto consider = [&](const Vec3& start, const Vec3& end) {
        const std::optional<Vec3> change = first_change(image, start, end, step_mm, background);
        if (!change) return;
        double clearance = std::numeric_limits<double>::infinity();
        for (const Vec3& corner : v) clearance = std::min(clearance, distance(*change, corner));
        if (clearance > best_clearance) best_clearance = clearance, best = change;
    };
    if (placement == Placement::material_centroid) {
        const Vec3 c = centroid(v);
        for (const Vec3& corner : v) consider(c, corner);
        return best;
    }
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
            const Vec3 middle = 0.5 * (v[i] + v[j]);
            consider(middle, v[i]);
            consider(middle, v[j]);
        }
    return best;
}

} // namespace

Label voxel_label_at(const LabelImage& image, const Vec3& world_mm, Label background)
{
    const Vec3 index = image.world_to_index(world_mm);
    const Index3 nearest{static_cast<std::int64_t>(std::floor(index[0] + 0.5)),
                         static_cast<std::int64_t>(std::floor(index[1] + 0.5)),
                         static_cast<std::int64_t>(std::floor(index[2] + 0.5))};
    if (!image.contains(nearest)) return background;
    return image.at(static_cast<std::size_t>(nearest[0]), static_cast<std::size_t>(nearest[1]),
                    static_cast<std::size_t>(nearest[2]));
}

Vec3 place_node(const LabelImage& image, const std::array<Vec3, 4>& corners, Placement placement, Label background,
                bool interior)
{
    Vec3 point = centroid(corners);
    switch (placement) {
    case Placement::centroid: break;
    case Placement::incentre: point = incentre(corners); break;
    case Placement::longest_edge: point = longest_edge_midpoint(corners); break;
    case Placement::material_half_edges:
    case Placement::material_centroid:
        point = material_change(image, corners, placement, background).value_or(point);
        break;
    }
    if (!interior) return point;
    std::array<double, 4> weight = barycentric(corners, point);
    double sum = 0;
    for (double& w : weight) w = std::max(0.0, w), sum += w;
    Vec3 pulled{0, 0, 0};
    for (int i = 0; i < 4; ++i) pulled = pulled + (min_weight + (1 - 4 * min_weight) * weight[i] / sum) * corners[i];
    return pulled;
}

} // namespace tissuemesh::volume::detail

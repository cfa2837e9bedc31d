#include "surface/detail/voxel_sides.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace tissuemesh::surface::detail {
namespace {

/// A direction along no axis, plane diagonal or space diagonal of the grid, so that rays from voxel centres seldom
/// run along the planes surface nets put vertices on.
const Vec3 ray_direction = [] {
    const Vec3 d{0.5773, 0.5801, 0.5749};
    return (1 / norm(d)) * d;
}();
constexpr double infinity = std::numeric_limits<double>::infinity();
/// Two unit directions across the ray and across each other.
const std::array<Vec3, 2> across = [] {
    const Vec3 first = cross(ray_direction, Vec3{1, 0, 0});
    const Vec3 u = (1 / norm(first)) * first;
    return std::array<Vec3, 2>{u, cross(ray_direction, u)};
}();

} // namespace

VoxelSides::VoxelSides(const LabelImage& image) : image_(image), next_to_other_(image.voxel_count(), 0)
{
    const Dims& n = image.dims();
    const auto at = [&](std::size_t i, std::size_t j, std::size_t k) { return image.at(i, j, k); };
#pragma omp parallel for schedule(static)
    for (std::int64_t kk = 0; kk < static_cast<std::int64_t>(n[2]); ++kk) {
        const auto k = static_cast<std::size_t>(kk);
        for (std::size_t j = 0; j < n[1]; ++j)
            for (std::size_t i = 0; i < n[0]; ++i) {
                const Label l = at(i, j, k);
                next_to_other_[image.linear_index(i, j, k)] =
                    (i > 0 && at(i - 1, j, k) != l) || (i + 1 < n[0] && at(i + 1, j, k) != l) ||
                    (j > 0 && at(i, j - 1, k) != l) || (j + 1 < n[1] && at(i, j + 1, k) != l) ||
                    (k > 0 && at(i, j, k - 1) != l) || (k + 1 < n[2] && at(i, j, k + 1) != l);
            }
    }
}

bool VoxelSides::carries_a_centre(const std::vector<TriangleCorners>& before,
                                  const std::vector<TriangleCorners>& after) const
{
    // Each triangle's shadow along the ray: the box of its corners in two directions across the ray, and how far
    // along the ray it reaches. A ray can only meet a triangle whose shadow holds its origin, and that reaches
    // beyond it; the shadows are widened by far more than any rounding of the exact test, which then decides.
    constexpr double widen = 1e-6; // mm
    struct Shadow {
        double low1, high1, low2, high2, reach;
    };
    constexpr std::size_t few = 64;
    std::array<Shadow, few> kept; // each used one is written before it is read
    std::vector<Shadow> many;
    const std::size_t count = before.size() + after.size();
    if (count > few) many.resize(count);
    Shadow* shadows = count > few ? many.data() : kept.data();
    // The voxels whose centres lie in the index box of every corner (any orientation of the image).
    Vec3 low{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
             std::numeric_limits<double>::max()};
    Vec3 high = -1.0 * low;
    std::size_t n = 0;
    for (const auto* triangles : {&before, &after})
        for (const TriangleCorners& c : *triangles) {
            Shadow& s = shadows[n++];
            s = {infinity, -infinity, infinity, -infinity, -infinity};
            for (const Vec3& p : c) {
                const Vec3 x = image_.world_to_index(p);
                for (int a = 0; a < 3; ++a) low[a] = std::min(low[a], x[a]), high[a] = std::max(high[a], x[a]);
                const double x1 = dot(p, across[0]), x2 = dot(p, across[1]);
                s.low1 = std::min(s.low1, x1), s.high1 = std::max(s.high1, x1);
                s.low2 = std::min(s.low2, x2), s.high2 = std::max(s.high2, x2);
                s.reach = std::max(s.reach, dot(p, ray_direction));
            }
            s.low1 -= widen, s.high1 += widen, s.low2 -= widen, s.high2 += widen, s.reach += widen;
        }
    std::array<std::int64_t, 3> from{}, to{};
    for (int a = 0; a < 3; ++a) {
        from[a] = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::ceil(low[a])));
        to[a] = std::min<std::int64_t>(static_cast<std::int64_t>(image_.dims()[a]) - 1,
                                       static_cast<std::int64_t>(std::floor(high[a])));
    }
    for (std::int64_t k = from[2]; k <= to[2]; ++k)
        for (std::int64_t j = from[1]; j <= to[1]; ++j)
            for (std::int64_t i = from[0]; i <= to[0]; ++i) {
                if (!next_to_other_[image_.linear_index(static_cast<std::size_t>(i), static_cast<std::size_t>(j),
                                                        static_cast<std::size_t>(k))])
                    continue;
                const Vec3 centre =
                    image_.index_to_world({static_cast<double>(i), static_cast<double>(j), static_cast<double>(k)});
                const double x1 = dot(centre, across[0]), x2 = dot(centre, across[1]),
                             depth = dot(centre, ray_direction);
                bool inside = false;
                n = 0;
                for (const auto* triangles : {&before, &after})
                    for (const TriangleCorners& c : *triangles) {
                        const Shadow& s = shadows[n++];
                        if (x1 < s.low1 || x1 > s.high1 || x2 < s.low2 || x2 > s.high2 || depth > s.reach) continue;
                        inside ^= ray_meets_triangle(centre, ray_direction, c, infinity).has_value();
                    }
                if (inside) return true;
            }
    return false;
}

} // namespace tissuemesh::surface::detail

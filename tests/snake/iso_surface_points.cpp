#include "tests/snake/iso_surface_points.h"

#include <algorithm>
#include <cmath>

namespace tissuemesh::testing {

IsoSurfacePoints::IsoSurfacePoints(const surface::PotentialField& field, int lines_per_voxel)
{
    const Dims& dims = field.dims();
    const auto to_world = [&](const Vec3& index) { return field.index_to_world(index); };
    const double step = 1.0 / lines_per_voxel;
    for (std::size_t axis = 0; axis < 3; ++axis) {
        const std::size_t u = (axis + 1) % 3, v = (axis + 2) % 3;
        const double nu = static_cast<double>(dims[u] - 1), nv = static_cast<double>(dims[v] - 1);
        for (double a = 0; a <= nu + 1e-9; a += step)
            for (double b = 0; b <= nv + 1e-9; b += step) {
                Vec3 index{0, 0, 0};
                index[u] = a;
                index[v] = b;
                double previous = 0;
                for (std::size_t c = 0; c < dims[axis]; ++c) {
                    index[axis] = static_cast<double>(c);
                    const double value = field.value(to_world(index));
                    if (c > 0 && (previous < 0) != (value < 0) && previous != value) {
                        Vec3 zero = index;
                        zero[axis] = static_cast<double>(c) - value / (value - previous);
                        points_.push_back(to_world(zero));
                    }
                    previous = value;
                }
            }
    }
    Vec3 high{-1e300, -1e300, -1e300};
    low_ = {1e300, 1e300, 1e300};
    for (const Vec3& p : points_)
        for (std::size_t a = 0; a < 3; ++a) {
            low_[a] = std::min(low_[a], p[a]);
            high[a] = std::max(high[a], p[a]);
        }
    cell_mm_ = field.smallest_spacing_mm();
    for (std::size_t a = 0; a < 3; ++a) counts_[a] = static_cast<std::int64_t>((high[a] - low_[a]) / cell_mm_) + 1;
    cells_.resize(static_cast<std::size_t>(counts_[0] * counts_[1] * counts_[2]));
    for (std::uint32_t n = 0; n < points_.size(); ++n) {
        const auto c = cell_of(points_[n]);
        cells_[static_cast<std::size_t>(c[0] + counts_[0] * (c[1] + counts_[1] * c[2]))].push_back(n);
    }
}

std::array<std::int64_t, 3> IsoSurfacePoints::cell_of(const Vec3& p) const
{
    std::array<std::int64_t, 3> c{};
    for (std::size_t a = 0; a < 3; ++a)
        c[a] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((p[a] - low_[a]) / cell_mm_)), 0,
                                        counts_[a] - 1);
    return c;
}

double IsoSurfacePoints::distance(const Vec3& p, double max_mm) const
{
    const auto centre = cell_of(p);
    double best = max_mm;
    // Rings of cells outwards until the ring is farther than the best distance found.
    const std::int64_t max_ring = static_cast<std::int64_t>(max_mm / cell_mm_) + 1;
    for (std::int64_t ring = 0; ring <= max_ring; ++ring) {
        if (static_cast<double>(ring - 1) * cell_mm_ > best) break;
        for (std::int64_t k = centre[2] - ring; k <= centre[2] + ring; ++k)
            for (std::int64_t j = centre[1] - ring; j <= centre[1] + ring; ++j)
                for (std::int64_t i = centre[0] - ring; i <= centre[0] + ring; ++i) {
                    if (std::max({std::abs(i - centre[0]), std::abs(j - centre[1]), std::abs(k - centre[2])}) != ring)
                        continue;
                    if (i < 0 || j < 0 || k < 0 || i >= counts_[0] || j >= counts_[1] || k >= counts_[2]) continue;
                    for (const std::uint32_t n :
                         cells_[static_cast<std::size_t>(i + counts_[0] * (j + counts_[1] * k))])
                        best = std::min(best, tissuemesh::distance(p, points_[n]));
                }
    }
    return best;
}

} // namespace tissuemesh::testing

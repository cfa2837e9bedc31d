#include "surface/detail/layer_sizing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "surface/detail/box_index.h"
#include "surface/detail/triangle_distance.h"

namespace tissuemesh::surface::detail {

LayerSizing::LayerSizing(const InterfaceComplex& complex, Label background, const LayerSizingOptions& options)
    : target_mm_(options.target_edge_mm)
{
    if (!(options.edges_per_mm > 0) || !(options.target_edge_mm > 0) || complex.triangles.empty()) return;
    const double smallest = std::clamp(options.min_edge_mm, 1e-3, options.target_edge_mm);
    // Thicker than this, a layer takes the target as it is.
    const double reach = options.target_edge_mm / options.edges_per_mm;
    const auto corners = [&](std::uint32_t t) {
        const Triangle& tri = complex.triangles[t];
        return TriangleCorners{complex.vertices[tri[0]], complex.vertices[tri[1]], complex.vertices[tri[2]]};
    };
    std::vector<CompactBox> boxes(complex.triangle_count());
    std::vector<std::uint32_t> ids(complex.triangle_count());
    Box3 all{complex.vertices[complex.triangles[0][0]], complex.vertices[complex.triangles[0][0]]};
    for (std::uint32_t t = 0; t < complex.triangle_count(); ++t) {
        const Box3 box = bounding_box(corners(t));
        boxes[t] = compact(box), ids[t] = t;
        all = box_union(all, box);
    }
    const BoxIndex index(boxes, ids);
    // The grid: cells of a third of the target (at least the smallest edge), fewer when too many.
    cell_mm_ = std::max(smallest, options.target_edge_mm / 3);
    const auto count_cells = [&] {
        for (int a = 0; a < 3; ++a) {
            origin_[a] = all.low[a] - cell_mm_;
            counts_[a] = static_cast<std::int64_t>((all.high[a] - all.low[a]) / cell_mm_) + 3;
        }
        return static_cast<double>(counts_[0]) * static_cast<double>(counts_[1]) * static_cast<double>(counts_[2]);
    };
    while (count_cells() > 1 << 24) cell_mm_ *= 1.25;
    size_.assign(static_cast<std::size_t>(counts_[0] * counts_[1] * counts_[2]),
                 static_cast<float>(options.target_edge_mm));
    const auto cell_of = [&](const Vec3& p) {
        std::array<std::int64_t, 3> c{};
        for (int a = 0; a < 3; ++a)
            c[a] = std::clamp(static_cast<std::int64_t>(std::floor((p[a] - origin_[a]) / cell_mm_)), std::int64_t{0},
                              counts_[a] - 1);
        return c;
    };
    const auto index_of = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
        return static_cast<std::size_t>(i + counts_[0] * (j + counts_[1] * k));
    };
    // Each triangle: the thinnest of the layers on its sides (rays cast side by side, each on its own, so the
    // result does not depend on the threads), as a target on the cells its box overlaps.
    const auto triangles = static_cast<std::int64_t>(complex.triangle_count());
    std::vector<double> thickness(complex.triangle_count(), reach);
#pragma omp parallel for schedule(dynamic, 4096)
    for (std::int64_t i = 0; i < triangles; ++i) {
        const auto t = static_cast<std::uint32_t>(i);
        const TriangleCorners c = corners(t);
        const Vec3 normal = cross(c[1] - c[0], c[2] - c[0]);
        const double area2 = norm(normal);
        if (!(area2 > 0)) continue;
        const Vec3 n = (1 / area2) * normal;
        const Vec3 centre = (1.0 / 3.0) * (c[0] + c[1] + c[2]);
        double& thinnest = thickness[t];
        for (const int sign : {1, -1}) {
            // Normals point from `from` into `to`.
            const Label tissue = sign > 0 ? complex.sides[t].to : complex.sides[t].from;
            if (tissue == background) continue;
            const Vec3 d = static_cast<double>(sign) * n;
            const Vec3 end = centre + reach * d;
            Box3 ray{centre, centre};
            for (int a = 0; a < 3; ++a)
                ray.low[a] = std::min(centre[a], end[a]), ray.high[a] = std::max(centre[a], end[a]);
            index.visit(ray, [&](std::uint32_t u) {
                if (u == t) return;
                if (const std::optional<double> hit = ray_meets_triangle(centre, d, corners(u), thinnest))
                    thinnest = *hit;
            });
        }
    }
    for (std::uint32_t t = 0; t < complex.triangle_count(); ++t) {
        if (!(thickness[t] < reach)) continue;
        ++thin_triangles_;
        const auto size = static_cast<float>(std::max(smallest, options.edges_per_mm * thickness[t]));
        const Box3 box = bounding_box(corners(t));
        const auto low = cell_of(box.low), high = cell_of(box.high);
        for (std::int64_t k = low[2]; k <= high[2]; ++k)
            for (std::int64_t j = low[1]; j <= high[1]; ++j)
                for (std::int64_t i = low[0]; i <= high[0]; ++i) {
                    float& s = size_[index_of(i, j, k)];
                    s = std::min(s, size);
                }
    }
    // Grading: no cell more than `growth` per mm above a neighbour (a sweep each way, each from the 13
    // neighbours it has passed, as a chamfer distance transform).
    const auto grade = [&](int direction) {
        const std::int64_t nx = counts_[0], ny = counts_[1], nz = counts_[2];
        // The 13 neighbours swept before a cell (lower index forwards, higher backwards), with their distances.
        struct Neighbour {
            std::int64_t di, dj, dk, offset;
            double step;
        };
        std::vector<Neighbour> before;
        for (std::int64_t dk = -1; dk <= 1; ++dk)
            for (std::int64_t dj = -1; dj <= 1; ++dj)
                for (std::int64_t di = -1; di <= 1; ++di) {
                    const std::int64_t offset = di + nx * (dj + ny * dk);
                    if (offset == 0 || (offset < 0) != (direction > 0)) continue;
                    before.push_back(
                        {di, dj, dk, offset, cell_mm_ * std::sqrt(static_cast<double>(di * di + dj * dj + dk * dk))});
                }
        for (std::int64_t n = 0; n < nx * ny * nz; ++n) {
            const std::int64_t m = direction > 0 ? n : nx * ny * nz - 1 - n;
            const std::int64_t i = m % nx, j = (m / nx) % ny, k = m / (nx * ny);
            float& s = size_[static_cast<std::size_t>(m)];
            const bool inside = i > 0 && j > 0 && k > 0 && i + 1 < nx && j + 1 < ny && k + 1 < nz;
            for (const Neighbour& b : before) {
                if (!inside) {
                    const std::int64_t a = i + b.di, c = j + b.dj, d = k + b.dk;
                    if (a < 0 || c < 0 || d < 0 || a >= nx || c >= ny || d >= nz) continue;
                }
                s = std::min(
                    s, static_cast<float>(size_[static_cast<std::size_t>(m + b.offset)] + options.growth * b.step));
            }
        }
    };
    grade(1);
    grade(-1);
}

double LayerSizing::at(const Vec3& p) const
{
    if (size_.empty()) return target_mm_;
    std::array<std::int64_t, 3> c{};
    for (int a = 0; a < 3; ++a) {
        const double x = std::floor((p[a] - origin_[a]) / cell_mm_);
        if (x < 0 || x >= static_cast<double>(counts_[a])) return target_mm_;
        c[a] = static_cast<std::int64_t>(x);
    }
    return size_[static_cast<std::size_t>(c[0] + counts_[0] * (c[1] + counts_[1] * c[2]))];
}

double LayerSizing::smallest_mm() const
{
    return size_.empty() ? target_mm_ : static_cast<double>(*std::min_element(size_.begin(), size_.end()));
}

} // namespace tissuemesh::surface::detail

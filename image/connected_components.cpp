#include "image/connected_components.h"

#include <array>
#include <limits>

#include "core/error.h"

namespace tissuemesh::image {
namespace {

/// Union-find whose roots are the smallest voxel index of their set, so that a set's root is met
/// first in a raster scan.
class DisjointSets {
public:
    explicit DisjointSets(std::size_t count) : parent_(count)
    {
        for (std::size_t v = 0; v < count; ++v) parent_[v] = static_cast<std::uint32_t>(v);
    }
    std::uint32_t find(std::uint32_t v)
    {
        while (parent_[v] != v) {
            parent_[v] = parent_[parent_[v]]; // path halving
            v = parent_[v];
        }
        return v;
    }
    void unite(std::uint32_t a, std::uint32_t b)
    {
        a = find(a), b = find(b);
        if (a < b) parent_[b] = a;
        else if (b < a) parent_[a] = b;
    }
    std::uint32_t parent(std::uint32_t v) const { return parent_[v]; }

private:
    std::vector<std::uint32_t> parent_;
};

/// Neighbour offsets that precede a voxel in memory order: 3 for faces, 13 for the full 26.
std::vector<std::array<int, 3>> backward_offsets(Connectivity connectivity)
{
    std::vector<std::array<int, 3>> offsets;
    for (int dk = -1; dk <= 0; ++dk)
        for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
                if (dk == 0 && (dj > 0 || (dj == 0 && di >= 0))) continue; // not before the voxel
                if (connectivity == Connectivity::faces6 && std::abs(di) + std::abs(dj) + std::abs(dk) != 1) continue;
                offsets.push_back({di, dj, dk});
            }
    return offsets;
}

} // namespace

Components find_components(const LabelImage& image, Connectivity connectivity)
{
    if (image.voxel_count() >= std::numeric_limits<std::uint32_t>::max())
        throw InputError(concat("label image of ", image.voxel_count(),
                                " voxels: components need fewer than 2^32; crop or resample it (tm-prep)"));
    const Dims& d = image.dims();
    const auto& labels = image.labels();
    const auto offsets = backward_offsets(connectivity);
    DisjointSets sets(image.voxel_count());
    const auto nx = static_cast<std::int64_t>(d[0]), ny = static_cast<std::int64_t>(d[1]);
    for (std::int64_t k = 0; k < static_cast<std::int64_t>(d[2]); ++k)
        for (std::int64_t j = 0; j < ny; ++j)
            for (std::int64_t i = 0; i < nx; ++i) {
                const std::int64_t v = i + nx * (j + ny * k);
                for (const auto& [di, dj, dk] : offsets) {
                    const std::int64_t a = i + di, b = j + dj, c = k + dk;
                    if (a < 0 || a >= nx || b < 0 || b >= ny || c < 0) continue;
                    const std::int64_t w = a + nx * (b + ny * c);
                    if (labels[w] == labels[v])
                        sets.unite(static_cast<std::uint32_t>(v), static_cast<std::uint32_t>(w));
                }
            }

    Components result;
    result.component.resize(image.voxel_count());
    for (std::size_t k = 0; k < d[2]; ++k)
        for (std::size_t j = 0; j < d[1]; ++j)
            for (std::size_t i = 0; i < d[0]; ++i) {
                const auto v = static_cast<std::uint32_t>(image.linear_index(i, j, k));
                const std::uint32_t root = sets.find(v);
                std::uint32_t id;
                if (root == v) {
                    id = static_cast<std::uint32_t>(result.count());
                    result.label.push_back(labels[v]);
                    result.size.push_back(0);
                    result.touches_border.push_back(false);
                } else {
                    id = result.component[root]; // the root precedes v in memory order
                }
                result.component[v] = id;
                ++result.size[id];
                if (i == 0 || j == 0 || k == 0 || i + 1 == d[0] || j + 1 == d[1] || k + 1 == d[2])
                    result.touches_border[id] = true;
            }
    return result;
}

} // namespace tissuemesh::image

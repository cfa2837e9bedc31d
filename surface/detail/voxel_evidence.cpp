#include "surface/detail/voxel_evidence.h"

#include <algorithm>
#include <cmath>

namespace tissuemesh::surface::detail {

VoxelEvidence::VoxelEvidence(const LabelImage& image, Label background, double depth_voxels)
    : image_(image), background_(background), depth_(depth_voxels)
{
}

/// Voxel n's cell is [n - 1/2, n + 1/2] per axis (index space). The cells within `depth` of x (at most
/// the 2 x 2 x 2 nearest for depth <= 1) are the voxels x is "near"; x may hold a vertex between
/// `tissues` when it is near all of them (three of them on a junction of more): within `depth` of every
/// side of the interface or junction curve it stands for.
bool VoxelEvidence::allows(const Vec3& position_mm, const std::vector<Label>& tissues) const
{
    const Vec3 x = image_.world_to_index(position_mm);
    std::array<std::int64_t, 3> low{}, high{};
    for (int a = 0; a < 3; ++a) {
        low[a] = static_cast<std::int64_t>(std::floor(x[a] - depth_ + 0.5));
        high[a] = static_cast<std::int64_t>(std::floor(x[a] + depth_ + 0.5));
    }
    std::array<Label, 8> near{};
    std::size_t count = 0;
    for (std::int64_t k = low[2]; k <= high[2]; ++k)
        for (std::int64_t j = low[1]; j <= high[1]; ++j)
            for (std::int64_t i = low[0]; i <= high[0]; ++i) {
                const std::array<std::int64_t, 3> n{i, j, k};
                double d2 = 0;
                for (int a = 0; a < 3; ++a) {
                    const double d = std::max(0.0, std::abs(x[a] - static_cast<double>(n[a])) - 0.5);
                    d2 += d * d;
                }
                if (d2 < depth_ * depth_ && count < near.size()) near[count++] = image_.at_or({i, j, k}, background_);
            }
    std::size_t own = 0;
    for (const Label tissue : tissues)
        own += std::find(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(count), tissue) !=
                       near.begin() + static_cast<std::ptrdiff_t>(count)
                   ? 1
                   : 0;
    return own >= std::min<std::size_t>(tissues.size(), 3);
}

} // namespace tissuemesh::surface::detail

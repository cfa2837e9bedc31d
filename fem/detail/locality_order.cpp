#include "fem/detail/locality_order.h"

#include <algorithm>
#include <limits>
#include <utility>

namespace tissuemesh::fem::detail {
namespace {

// The 21 low bits of `x` spread to every third bit of a 64-bit word.
std::uint64_t spread_bits(std::uint64_t x)
{
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffff;
    x = (x | x << 16) & 0x1f0000ff0000ff;
    x = (x | x << 8) & 0x100f00f00f00f00f;
    x = (x | x << 4) & 0x10c30c30c30c30c3;
    x = (x | x << 2) & 0x1249249249249249;
    return x;
}

} // namespace

std::vector<std::uint32_t> locality_order(const std::vector<Vec3>& nodes, const std::vector<bool>& keep)
{
    Vec3 low{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
             std::numeric_limits<double>::max()};
    Vec3 high{-low[0], -low[1], -low[2]};
    for (std::size_t i = 0; i < nodes.size(); ++i)
        if (keep[i])
            for (int a = 0; a < 3; ++a) {
                low[a] = std::min(low[a], nodes[i][a]);
                high[a] = std::max(high[a], nodes[i][a]);
            }
    constexpr double steps = (1 << 21) - 1;
    const double extent = std::max({high[0] - low[0], high[1] - low[1], high[2] - low[2], 1e-300});
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        if (!keep[i]) continue;
        std::uint64_t key = 0;
        for (int a = 0; a < 3; ++a)
            key |= spread_bits(static_cast<std::uint64_t>((nodes[i][a] - low[a]) / extent * steps)) << a;
        keyed.emplace_back(key, static_cast<std::uint32_t>(i));
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<std::uint32_t> order(keyed.size());
    for (std::size_t k = 0; k < keyed.size(); ++k) order[k] = keyed[k].second;
    return order;
}

} // namespace tissuemesh::fem::detail

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
    for (std::size_t i = 0; i < nodes.size(); ++i)
        if (keep[i]) keyed.emplace_back(0, static_cast<std::uint32_t>(i));
    const auto count = static_cast<std::int64_t>(keyed.size());
#pragma omp parallel for schedule(static)
    for (std::int64_t k = 0; k < count; ++k) {
        auto& [key, i] = keyed[static_cast<std::size_t>(k)];
        for (int a = 0; a < 3; ++a)
            key |= spread_bits(static_cast<std::uint64_t>((nodes[i][a] - low[a]) / extent * steps)) << a;
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<std::uint32_t> order(keyed.size());
    for (std::size_t k = 0; k < keyed.size(); ++k) order[k] = keyed[k].second;
    return order;
}

LocalMesh renumber_for_locality(const TetMesh& mesh)
{
    LocalMesh result;
    result.original = locality_order(mesh.vertices, std::vector<bool>(mesh.vertex_count(), true));
    result.local.resize(mesh.vertex_count());
    for (std::size_t k = 0; k < result.original.size(); ++k)
        result.local[result.original[k]] = static_cast<std::uint32_t>(k);
    TetMesh& out = result.mesh;
    out.vertices.resize(mesh.vertex_count());
    for (std::size_t k = 0; k < result.original.size(); ++k) out.vertices[k] = mesh.vertices[result.original[k]];
    // Counting sort of the tets by their smallest new node (stable: ties keep their order). The keys and the
    // copy run in parallel; only the positions are counted out in order.
    const auto tets = static_cast<std::int64_t>(mesh.tet_count());
    std::vector<std::uint32_t> position(mesh.tet_count());
#pragma omp parallel for schedule(static)
    for (std::int64_t t = 0; t < tets; ++t) {
        const Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
        position[static_cast<std::size_t>(t)] =
            std::min({result.local[tet[0]], result.local[tet[1]], result.local[tet[2]], result.local[tet[3]]});
    }
    std::vector<std::uint32_t> start(mesh.vertex_count() + 1, 0);
    for (std::uint32_t first : position) ++start[first + 1];
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) start[v + 1] += start[v];
    for (std::uint32_t& at : position) at = start[at]++;
    out.tets.resize(mesh.tet_count());
    out.tet_labels.resize(mesh.tet_count());
#pragma omp parallel for schedule(static)
    for (std::int64_t t = 0; t < tets; ++t) {
        const Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
        const std::uint32_t at = position[static_cast<std::size_t>(t)];
        out.tets[at] = {result.local[tet[0]], result.local[tet[1]], result.local[tet[2]], result.local[tet[3]]};
        out.tet_labels[at] = mesh.tet_labels[static_cast<std::size_t>(t)];
    }
    out.faces.reserve(mesh.faces.size());
    for (const Triangle& face : mesh.faces)
        out.faces.push_back({result.local[face[0]], result.local[face[1]], result.local[face[2]]});
    out.face_sides = mesh.face_sides;
    out.names = mesh.names;
    return result;
}

} // namespace tissuemesh::fem::detail

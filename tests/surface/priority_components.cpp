// The priority connectivity rule of extract_interfaces(), re-implemented from its header's text: lattice
// points are the padded voxel centres plus the centres of split cubes, joined by the edges of the
// tetrahedralization the rule describes.
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <numeric>

#include "tests/surface/complex_checks.h"

namespace tissuemesh::testing {
namespace {

struct Cube {
    std::array<Label, 8> labels{};
    std::vector<std::array<int, 2>> edges; ///< corner pairs joined inside the cube (centre: 8)
    Label centre = 0;
    bool split = false;
};

/// The edges of one cube's tetrahedralization under `rank` (unlisted labels: lowest).
Cube plan_cube(const std::array<Label, 8>& labels, const std::map<Label, int>& priority)
{
    const auto rank = [&](Label l) {
        const auto it = priority.find(l);
        return it == priority.end() ? std::numeric_limits<long long>::min() : static_cast<long long>(it->second);
    };
    Cube cube{labels, {}, 0, false};
    for (int c = 0; c < 8; ++c)
        for (int bit = 1; bit < 8; bit <<= 1)
            if (!(c & bit)) cube.edges.push_back({c, c | bit}); // the 12 cube edges
    bool any_anti = false;
    std::vector<std::array<int, 2>> diagonals;
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            const int u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
            const int low = side << axis, a = low | 1 << u, b = low | 1 << v, high = low | 1 << u | 1 << v;
            const Label t = labels[a];
            const bool anti =
                labels[b] == t && priority.contains(t) && rank(labels[low]) < rank(t) && rank(labels[high]) < rank(t);
            any_anti = any_anti || anti;
            diagonals.push_back(anti ? std::array<int, 2>{a, b} : std::array<int, 2>{low, high});
        }
    cube.edges.insert(cube.edges.end(), diagonals.begin(), diagonals.end());
    // Top label: highest rank, then most frequent, then smallest.
    std::array<Label, 8> sorted = labels;
    std::sort(sorted.begin(), sorted.end());
    cube.centre = sorted[0];
    for (const Label l : sorted) {
        const auto n = std::count(sorted.begin(), sorted.end(), l),
                   m = std::count(sorted.begin(), sorted.end(), cube.centre);
        if (rank(l) > rank(cube.centre) || (rank(l) == rank(cube.centre) && n > m)) cube.centre = l;
    }
    // Are the top label's corners joined by Kuhn edges (comparable corner pairs) inside the cube?
    std::array<int, 8> group{};
    std::iota(group.begin(), group.end(), 0);
    for (int pass = 0; pass < 8; ++pass)
        for (int x = 0; x < 8; ++x)
            for (int y = 0; y < 8; ++y)
                if (labels[x] == cube.centre && labels[y] == cube.centre && (x & y) == x)
                    group[x] = group[y] = std::min(group[x], group[y]);
    int groups = 0;
    for (int c = 0; c < 8; ++c) groups += labels[c] == cube.centre && group[c] == c;
    // Does the main diagonal 0-7 join two non-T corners that T separates inside the cube (no non-T
    // path of cube edges between them)?
    bool crosses = false;
    if (labels[0] != cube.centre && labels[7] != cube.centre) {
        std::vector<int> stack{0};
        std::array<bool, 8> seen{};
        seen[0] = true;
        while (!stack.empty()) {
            const int c = stack.back();
            stack.pop_back();
            for (const int bit : {1, 2, 4})
                if (!seen[c ^ bit] && labels[c ^ bit] != cube.centre) seen[c ^ bit] = true, stack.push_back(c ^ bit);
        }
        crosses = !seen[7];
    }
    cube.split = priority.contains(cube.centre) && (any_anti || groups > 1 || crosses);
    if (cube.split)
        for (int c = 0; c < 8; ++c) cube.edges.push_back({c, 8});
    else cube.edges.push_back({0, 7});
    return cube;
}

std::size_t root_of(std::vector<std::size_t>& parent, std::size_t x)
{
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
}

} // namespace

std::size_t priority_components(const LabelImage& image, Label label, Label background, bool complement,
                                const std::map<Label, int>& priority)
{
    const long long nx = static_cast<long long>(image.dims()[0]) + 2, ny = static_cast<long long>(image.dims()[1]) + 2,
                    nz = static_cast<long long>(image.dims()[2]) + 2;
    const auto at = [&](long long i, long long j, long long k) {
        const bool inside = i > 0 && j > 0 && k > 0 && i < nx - 1 && j < ny - 1 && k < nz - 1;
        return inside ? image.at(static_cast<std::size_t>(i - 1), static_cast<std::size_t>(j - 1),
                                 static_cast<std::size_t>(k - 1))
                      : background;
    };
    const auto points = static_cast<std::size_t>(nx * ny * nz);
    // Ids: grid points first, then one centre slot per cube (used only by split cubes).
    std::vector<std::size_t> parent(2 * points);
    std::iota(parent.begin(), parent.end(), std::size_t{0});
    std::vector<char> member(2 * points, 0);
    const auto is_member = [&](Label l) { return (l == label) != complement; };
    for (long long k = 0; k < nz; ++k)
        for (long long j = 0; j < ny; ++j)
            for (long long i = 0; i < nx; ++i)
                member[static_cast<std::size_t>(i + nx * (j + ny * k))] = is_member(at(i, j, k));
    for (long long k = 0; k + 1 < nz; ++k)
        for (long long j = 0; j + 1 < ny; ++j)
            for (long long i = 0; i + 1 < nx; ++i) {
                std::array<Label, 8> labels{};
                std::array<std::size_t, 9> ids{};
                for (int c = 0; c < 8; ++c) {
                    const long long a = i + (c & 1), b = j + (c >> 1 & 1), d = k + (c >> 2 & 1);
                    labels[c] = at(a, b, d);
                    ids[c] = static_cast<std::size_t>(a + nx * (b + ny * d));
                }
                ids[8] = points + static_cast<std::size_t>(i + nx * (j + ny * k));
                const Cube cube = plan_cube(labels, priority);
                if (cube.split) member[ids[8]] = is_member(cube.centre);
                for (const auto& [x, y] : cube.edges)
                    if (member[ids[x]] && member[ids[y]]) parent[root_of(parent, ids[x])] = root_of(parent, ids[y]);
            }
    std::size_t components = 0;
    for (std::size_t p = 0; p < parent.size(); ++p) components += member[p] && root_of(parent, p) == p;
    return components;
}

} // namespace tissuemesh::testing

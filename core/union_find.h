// Disjoint sets over 0..n-1 with path halving: the connected pieces of surfaces (edge-connected triangles) and
// of meshes (face-connected tets of one tissue).
#pragma once

#include <cstdint>
#include <numeric>
#include <vector>

namespace tissuemesh {

class UnionFind {
public:
    explicit UnionFind(std::size_t size) : parent_(size) { std::iota(parent_.begin(), parent_.end(), 0u); }
    std::uint32_t find(std::uint32_t x)
    {
        while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
        return x;
    }
    void unite(std::uint32_t a, std::uint32_t b) { parent_[find(a)] = find(b); }
    /// How many sets there are.
    std::size_t roots()
    {
        std::size_t count = 0;
        for (std::uint32_t x = 0; x < parent_.size(); ++x) count += find(x) == x ? 1 : 0;
        return count;
    }

private:
    std::vector<std::uint32_t> parent_;
};

} // namespace tissuemesh

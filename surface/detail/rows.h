// Rows: lists per index in one array (compressed rows), for per-vertex and per-triangle neighbourhoods.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace tissuemesh::surface::detail {

struct Rows {
    std::vector<std::uint32_t> offsets{0}; ///< #rows + 1
    std::vector<std::uint32_t> items;
    std::size_t size() const { return offsets.size() - 1; }
    std::span<const std::uint32_t> operator[](std::size_t i) const
    {
        return {items.data() + offsets[i], items.data() + offsets[i + 1]};
    }
};

/// Rows of `rows` lists from (row, item) pairs; each row keeps its items in the order given.
inline Rows group_rows(std::size_t rows, const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs)
{
    Rows out;
    out.offsets.assign(rows + 1, 0);
    for (const auto& entry : pairs) ++out.offsets[entry.first + 1];
    for (std::size_t r = 0; r < rows; ++r) out.offsets[r + 1] += out.offsets[r];
    out.items.resize(pairs.size());
    std::vector<std::uint32_t> next(out.offsets.begin(), out.offsets.end() - 1);
    for (const auto& [row, item] : pairs) out.items[next[row]++] = item;
    return out;
}

} // namespace tissuemesh::surface::detail

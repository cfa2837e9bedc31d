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

/// Per vertex (below `vertex_count`), the triangles holding it, in triangle order (a counting sort).
template <class Triangles>
Rows star_rows(const Triangles& triangles, std::size_t vertex_count)
{
    Rows out;
    out.offsets.assign(vertex_count + 1, 0);
    for (const auto& t : triangles)
        for (const std::uint32_t v : t) ++out.offsets[v + 1];
    for (std::size_t v = 0; v < vertex_count; ++v) out.offsets[v + 1] += out.offsets[v];
    out.items.resize(out.offsets.back());
    std::vector<std::uint32_t> next(out.offsets.begin(), out.offsets.end() - 1);
    for (std::size_t t = 0; t < triangles.size(); ++t)
        for (const std::uint32_t v : triangles[t]) out.items[next[v]++] = static_cast<std::uint32_t>(t);
    return out;
}

/// Rows from how many items each row has (`count`) and the items of consecutive blocks of rows, block after block
/// (as loops over blocks of rows side by side leave them).
inline Rows join_rows(const std::vector<std::uint32_t>& count, const std::vector<std::vector<std::uint32_t>>& blocks)
{
    Rows rows;
    rows.offsets.resize(count.size() + 1);
    rows.offsets[0] = 0;
    for (std::size_t r = 0; r < count.size(); ++r) rows.offsets[r + 1] = rows.offsets[r] + count[r];
    rows.items.reserve(rows.offsets.back());
    for (const std::vector<std::uint32_t>& items : blocks)
        rows.items.insert(rows.items.end(), items.begin(), items.end());
    return rows;
}

} // namespace tissuemesh::surface::detail

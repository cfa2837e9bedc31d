#include "surface/detail/triangle_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tissuemesh::surface::detail {

Box3 bounding_box(const TriangleCorners& t, double margin)
{
    Box3 box;
    for (int i = 0; i < 3; ++i) {
        box.low[i] = std::min({t[0][i], t[1][i], t[2][i]}) - margin;
        box.high[i] = std::max({t[0][i], t[1][i], t[2][i]}) + margin;
    }
    return box;
}

bool boxes_overlap(const Box3& a, const Box3& b)
{
    for (int i = 0; i < 3; ++i)
        if (a.high[i] < b.low[i] || b.high[i] < a.low[i]) return false;
    return true;
}

CompactBox compact(const Box3& box)
{
    CompactBox out;
    for (int i = 0; i < 3; ++i) {
        out.low[i] = std::nextafter(static_cast<float>(box.low[i]), -std::numeric_limits<float>::infinity());
        out.high[i] = std::nextafter(static_cast<float>(box.high[i]), std::numeric_limits<float>::infinity());
    }
    return out;
}

Box3 box_union(const Box3& a, const Box3& b)
{
    Box3 box;
    for (int i = 0; i < 3; ++i) {
        box.low[i] = std::min(a.low[i], b.low[i]);
        box.high[i] = std::max(a.high[i], b.high[i]);
    }
    return box;
}

TriangleGrid::TriangleGrid(const Box3& bounds, double cell_mm, std::size_t triangle_slots, std::size_t max_cells)
    : origin_(bounds.low), cell_mm_(cell_mm > 0 ? cell_mm : 1), seen_(triangle_slots, 0)
{
    const auto count_for = [&](double cell) {
        std::array<std::int64_t, 3> counts{};
        for (int i = 0; i < 3; ++i)
            counts[i] = std::max<std::int64_t>(
                1, static_cast<std::int64_t>(std::ceil((bounds.high[i] - bounds.low[i]) / cell)));
        return counts;
    };
    counts_ = count_for(cell_mm_);
    while (static_cast<double>(counts_[0]) * static_cast<double>(counts_[1]) * static_cast<double>(counts_[2]) >
           static_cast<double>(max_cells)) {
        cell_mm_ *= 1.25;
        counts_ = count_for(cell_mm_);
    }
    cells_.resize(static_cast<std::size_t>(counts_[0] * counts_[1] * counts_[2]));
}

std::array<std::int64_t, 3> TriangleGrid::cell_of(const Vec3& p) const
{
    std::array<std::int64_t, 3> c{};
    for (int i = 0; i < 3; ++i) {
        const double x = std::floor((p[i] - origin_[i]) / cell_mm_);
        c[i] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::clamp(x, -1.0, 1e15)), 0, counts_[i] - 1);
    }
    return c;
}

template <class Visit>
void TriangleGrid::for_cells(const Box3& box, Visit visit)
{
    const auto low = cell_of(box.low), high = cell_of(box.high);
    for (std::int64_t k = low[2]; k <= high[2]; ++k)
        for (std::int64_t j = low[1]; j <= high[1]; ++j)
            for (std::int64_t i = low[0]; i <= high[0]; ++i)
                visit(cells_[static_cast<std::size_t>(i + counts_[0] * (j + counts_[1] * k))]);
}

void TriangleGrid::insert(std::uint32_t t, const Box3& box)
{
    if (t >= seen_.size()) seen_.resize(static_cast<std::size_t>(t) + 1 + seen_.size() / 2, 0);
    for_cells(box, [t](std::vector<std::uint32_t>& cell) { cell.push_back(t); });
}

void TriangleGrid::erase(std::uint32_t t, const Box3& box)
{
    for_cells(box, [t](std::vector<std::uint32_t>& cell) {
        const auto it = std::find(cell.begin(), cell.end(), t);
        if (it != cell.end()) {
            *it = cell.back();
            cell.pop_back();
        }
    });
}

void TriangleGrid::query(const Box3& box, std::vector<std::uint32_t>& out)
{
    out.clear();
    if (++query_id_ == 0) {
        std::fill(seen_.begin(), seen_.end(), 0);
        query_id_ = 1;
    }
    for_cells(box, [&](const std::vector<std::uint32_t>& cell) {
        for (const std::uint32_t t : cell)
            if (seen_[t] != query_id_) {
                seen_[t] = query_id_;
                out.push_back(t);
            }
    });
}

} // namespace tissuemesh::surface::detail

#include "surface/detail/box_index.h"

#include <algorithm>

namespace tissuemesh::surface::detail {
namespace {

constexpr std::size_t max_cells = std::size_t{1} << 23;
/// A box is filed once when every side is at most this fraction of a cell (the margin keeps the one-cell
/// reach of visit() safe from rounding).
constexpr double small_fraction = 0.99;

double largest_side(const CompactBox& b)
{
    return std::max({static_cast<double>(b.high[0]) - b.low[0], static_cast<double>(b.high[1]) - b.low[1],
                     static_cast<double>(b.high[2]) - b.low[2]});
}

} // namespace

BoxIndex::BoxIndex(const std::vector<CompactBox>& boxes, const std::vector<std::uint32_t>& ids)
{
    if (ids.empty()) return;
    Box3 bounds{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
    for (const std::uint32_t id : ids) {
        const CompactBox& b = boxes[id];
        for (int a = 0; a < 3; ++a) {
            bounds.low[a] = std::min(bounds.low[a], static_cast<double>(b.low[a]));
            bounds.high[a] = std::max(bounds.high[a], static_cast<double>(b.high[a]));
        }
    }
    // Cells as large as nine boxes in ten (the tenth is filed in every cell it overlaps; the fraction is
    // estimated on at most 65 536 boxes spread over the list), fewer than max_cells, and not so small that
    // large boxes fill more than a few cells each.
    const std::size_t step = std::max<std::size_t>(1, ids.size() / 65536);
    std::vector<double> sides;
    for (std::size_t n = 0; n < ids.size(); n += step) sides.push_back(largest_side(boxes[ids[n]]));
    const auto tenth = sides.begin() + static_cast<std::ptrdiff_t>(sides.size() * 9 / 10);
    std::nth_element(sides.begin(), tenth, sides.end());
    const double span = std::max(
        {bounds.high[0] - bounds.low[0], bounds.high[1] - bounds.low[1], bounds.high[2] - bounds.low[2], 1e-9});
    cell_mm_ = std::max(*tenth / small_fraction, 1e-6 * span);
    origin_ = bounds.low;
    // Per id its cell (small boxes) or `none` (big ones), for the cell size that keeps the filings few.
    constexpr std::uint32_t none = static_cast<std::uint32_t>(-1);
    std::vector<std::uint32_t> cell_of_id(ids.size());
    const auto index = [&](const std::array<std::int64_t, 3>& c) {
        return static_cast<std::size_t>(c[0] + counts_[0] * (c[1] + counts_[1] * c[2]));
    };
    const auto low_cell = [&](const CompactBox& b) { return cell_of({b.low[0], b.low[1], b.low[2]}); };
    const auto high_cell = [&](const CompactBox& b) { return cell_of({b.high[0], b.high[1], b.high[2]}); };
    for (;;) {
        double cells = 1;
        for (int a = 0; a < 3; ++a) {
            counts_[a] = std::max<std::int64_t>(
                1, static_cast<std::int64_t>(std::ceil((bounds.high[a] - bounds.low[a]) / cell_mm_)));
            cells *= static_cast<double>(counts_[a]);
        }
        if (cells > static_cast<double>(max_cells)) {
            cell_mm_ *= 1.25;
            continue;
        }
        std::uint64_t filings = 0;
        for (std::size_t n = 0; n < ids.size(); ++n) {
            const CompactBox& b = boxes[ids[n]];
            if (largest_side(b) <= small_fraction * cell_mm_) {
                cell_of_id[n] = static_cast<std::uint32_t>(index(low_cell(b)));
                ++filings;
                continue;
            }
            cell_of_id[n] = none;
            const auto lo = low_cell(b), hi = high_cell(b);
            filings += static_cast<std::uint64_t>((hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1));
        }
        if (filings <= 8 * ids.size() + 1024) break;
        cell_mm_ *= 1.5;
    }
    const auto for_each_cell = [&](const CompactBox& b, auto action) {
        const auto lo = low_cell(b), hi = high_cell(b);
        for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
            for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
                for (std::int64_t i = lo[0]; i <= hi[0]; ++i) action(index({i, j, k}));
    };
    const std::size_t cells = static_cast<std::size_t>(counts_[0] * counts_[1] * counts_[2]);
    small_start_.assign(cells + 1, 0);
    big_start_.assign(cells + 1, 0);
    for (std::size_t n = 0; n < ids.size(); ++n) {
        if (cell_of_id[n] != none) ++small_start_[cell_of_id[n] + 1];
        else for_each_cell(boxes[ids[n]], [&](std::size_t c) { ++big_start_[c + 1]; });
    }
    for (std::size_t c = 1; c <= cells; ++c) {
        small_start_[c] += small_start_[c - 1];
        big_start_[c] += big_start_[c - 1];
    }
    small_.resize(small_start_.back());
    big_.resize(big_start_.back());
    std::uint32_t largest_id = 0;
    for (const std::uint32_t id : ids) largest_id = std::max(largest_id, id);
    where_.assign(static_cast<std::size_t>(largest_id) + 1, none);
    // The starts serve as the cells' cursors while they fill (each ends at the next cell's start).
    for (std::size_t n = 0; n < ids.size(); ++n) {
        const CompactBox& b = boxes[ids[n]];
        const Entry entry{b, ids[n]};
        if (cell_of_id[n] != none) {
            const std::uint32_t e = small_start_[cell_of_id[n]]++;
            small_[e] = entry;
            where_[ids[n]] = e;
        } else {
            for_each_cell(b, [&](std::size_t c) {
                const std::uint32_t e = big_start_[c]++;
                big_[e] = entry;
                where_[ids[n]] = e | big_bit;
            });
        }
    }
    // Back to the starts: each cell's cursor now holds the next cell's start.
    for (std::size_t c = cells; c > 0; --c) {
        small_start_[c] = small_start_[c - 1];
        big_start_[c] = big_start_[c - 1];
    }
    small_start_[0] = big_start_[0] = 0;
    if (big_.empty()) big_start_ = {};
}

const CompactBox& BoxIndex::filed_box(std::uint32_t id) const
{
    const std::uint32_t e = where_[id];
    return (e & big_bit) ? big_[e & ~big_bit].box : small_[e].box;
}

} // namespace tissuemesh::surface::detail

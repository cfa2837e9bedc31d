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
    std::vector<float> sides(ids.size());
    for (std::size_t n = 0; n < ids.size(); ++n) {
        const CompactBox& b = boxes[ids[n]];
        for (int a = 0; a < 3; ++a) {
            bounds.low[a] = std::min(bounds.low[a], static_cast<double>(b.low[a]));
            bounds.high[a] = std::max(bounds.high[a], static_cast<double>(b.high[a]));
        }
        sides[n] = static_cast<float>(largest_side(b));
    }
    // Cells as large as nine boxes in ten (the tenth is filed in every cell it overlaps), fewer than
    // max_cells, and not so small that large boxes fill more than a few cells each.
    const auto tenth = sides.begin() + static_cast<std::ptrdiff_t>(sides.size() * 9 / 10);
    std::nth_element(sides.begin(), tenth, sides.end());
    const double span = std::max({bounds.high[0] - bounds.low[0], bounds.high[1] - bounds.low[1],
                                  bounds.high[2] - bounds.low[2], 1e-9});
    cell_mm_ = std::max(static_cast<double>(*tenth) / small_fraction, 1e-6 * span);
    origin_ = bounds.low;
    std::vector<std::uint64_t> filings;
    for (;;) {
        double cells = 1;
        for (int a = 0; a < 3; ++a) {
            counts_[a] = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil((bounds.high[a] - bounds.low[a]) / cell_mm_)));
            cells *= static_cast<double>(counts_[a]);
        }
        if (cells > static_cast<double>(max_cells)) {
            cell_mm_ *= 1.25;
            continue;
        }
        // Per id its number of cells (0: small, filed once).
        std::uint64_t total = 0;
        filings.assign(ids.size(), 0);
        for (std::size_t n = 0; n < ids.size(); ++n) {
            const CompactBox& b = boxes[ids[n]];
            if (largest_side(b) <= small_fraction * cell_mm_) {
                ++total;
                continue;
            }
            const auto lo = cell_of({b.low[0], b.low[1], b.low[2]}), hi = cell_of({b.high[0], b.high[1], b.high[2]});
            filings[n] = static_cast<std::uint64_t>((hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1));
            total += filings[n];
        }
        if (total <= 8 * ids.size() + 1024) break;
        cell_mm_ *= 1.5;
    }
    const auto index = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
        return static_cast<std::size_t>(i + counts_[0] * (j + counts_[1] * k));
    };
    const std::size_t cells = static_cast<std::size_t>(counts_[0] * counts_[1] * counts_[2]);
    small_start_.assign(cells + 1, 0);
    big_start_.assign(cells + 1, 0);
    const auto low_cell = [&](const CompactBox& b) { return cell_of({b.low[0], b.low[1], b.low[2]}); };
    const auto for_each_cell = [&](const CompactBox& b, auto action) {
        const auto lo = low_cell(b), hi = cell_of({b.high[0], b.high[1], b.high[2]});
        for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
            for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
                for (std::int64_t i = lo[0]; i <= hi[0]; ++i) action(index(i, j, k));
    };
    for (std::size_t n = 0; n < ids.size(); ++n) {
        const CompactBox& b = boxes[ids[n]];
        if (filings[n] == 0) {
            const auto c = low_cell(b);
            ++small_start_[index(c[0], c[1], c[2]) + 1];
        } else {
            for_each_cell(b, [&](std::size_t c) { ++big_start_[c + 1]; });
        }
    }
    for (std::size_t c = 1; c <= cells; ++c) {
        small_start_[c] += small_start_[c - 1];
        big_start_[c] += big_start_[c - 1];
    }
    small_.resize(small_start_.back());
    big_.resize(big_start_.back());
    std::vector<std::uint32_t> next_small(small_start_.begin(), small_start_.end() - 1);
    std::vector<std::uint32_t> next_big(big_start_.begin(), big_start_.end() - 1);
    for (std::size_t n = 0; n < ids.size(); ++n) {
        const CompactBox& b = boxes[ids[n]];
        const Entry entry{b.low, b.high, ids[n]};
        if (filings[n] == 0) {
            const auto c = low_cell(b);
            small_[next_small[index(c[0], c[1], c[2])]++] = entry;
        } else {
            for_each_cell(b, [&](std::size_t c) { big_[next_big[c]++] = entry; });
        }
    }
    if (big_.empty()) big_start_ = {};
}

} // namespace tissuemesh::surface::detail

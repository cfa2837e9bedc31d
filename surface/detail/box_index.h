// BoxIndex: a static spatial index over many small boxes (triangle bounding boxes), for many queries
// against a set that does not change meanwhile: the batch judgements of ComplexEditor::move_together and
// the all-pairs search of the surface checker.
//
// Why not TriangleGrid: that grid files a triangle in every cell its box overlaps and keeps only indices,
// so a query visits each neighbour several times and reads its box elsewhere in memory (measured: about
// 100 visits for 10 boxes that overlap, on a 1 mm marching-cubes surface). Here a box no larger than a
// cell is filed once, in the cell of its low corner, with its coordinates stored next to it (entries sorted
// by cell), so a query reads a few runs of memory, each box once. The few boxes
// larger than a cell are filed in every cell they overlap and reported from one of them only.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "surface/detail/triangle_grid.h"

namespace tissuemesh::surface::detail {

class BoxIndex {
public:
    BoxIndex() = default;
    /// Files boxes[id] for every id of `ids` (distinct). The cell size follows the boxes' sizes.
    BoxIndex(const std::vector<CompactBox>& boxes, const std::vector<std::uint32_t>& ids);

    /// Calls visit(id) once for every filed id whose box overlaps `box` (closed boxes, compared as
    /// boxes_overlap(const Box3&, const CompactBox&) does), until visit returns true (when it returns a
    /// bool). Order: by cell, then as filed. Reads only.
    template <class Visit>
    void visit(const Box3& box, Visit visit) const
    {
        scan(box, 0, 0, [&](std::uint32_t id) {
            if constexpr (std::is_same_v<decltype(visit(id)), bool>) return visit(id);
            else return visit(id), false;
        });
    }

    /// Like visit(box, ...) with the box filed as `id`, but reporting only the ids that come after `id`: for
    /// two small boxes, by their place in the index (cell, then as filed), for a pair with a big box, by id.
    /// Visiting every filed id so reports each overlapping pair once, and reads about half the cells.
    template <class Visit>
    void visit_later(std::uint32_t id, const Box3& box, Visit visit) const
    {
        const std::uint32_t self = where_[id];
        if (self & big_bit) {
            scan(box, 0, 0, [&](std::uint32_t other) {
                if (other > id) visit(other);
                return false;
            });
            return;
        }
        scan(box, self + 1, id + 1, [&](std::uint32_t other) { return visit(other), false; });
    }

    double cell_mm() const { return cell_mm_; }
    /// The box `id` was filed with.
    /// @pre `id` was filed
    const CompactBox& filed_box(std::uint32_t id) const;

private:
    /// Calls stop(id) for every filed id whose box overlaps `box`, small ones only from entry `first_small` on,
    /// big ones only from id `first_big` on, until stop returns true.
    template <class Stop>
    void scan(const Box3& box, std::uint32_t first_small, std::uint32_t first_big, Stop stop) const
    {
        if (counts_[0] == 0) return;
        const auto low = cell_of(box.low), high = cell_of(box.high);
        // In single precision: u.low <= box.high exactly when u.low <= the largest float not above box.high.
        const std::array<float, 3> below{float_down(box.high[0]), float_down(box.high[1]), float_down(box.high[2])};
        const std::array<float, 3> above{float_up(box.low[0]), float_up(box.low[1]), float_up(box.low[2])};
        const auto overlaps = [&](const CompactBox& b) {
            return (b.low[0] <= below[0]) & (b.high[0] >= above[0]) & (b.low[1] <= below[1]) & (b.high[1] >= above[1]) &
                   (b.low[2] <= below[2]) & (b.high[2] >= above[2]);
        };
        // A small box overlapping `box` has its low corner at most one cell below box.low: in each row of
        // cells along x, one contiguous run of entries.
        const std::int64_t from_i = std::max<std::int64_t>(low[0] - 1, 0);
        for (std::int64_t k = std::max<std::int64_t>(low[2] - 1, 0); k <= high[2]; ++k)
            for (std::int64_t j = std::max<std::int64_t>(low[1] - 1, 0); j <= high[1]; ++j) {
                const std::int64_t row = counts_[0] * (j + counts_[1] * k);
                const std::uint32_t end = small_start_[static_cast<std::size_t>(row + high[0] + 1)];
                for (std::uint32_t e = std::max(small_start_[static_cast<std::size_t>(row + from_i)], first_small);
                     e < end; ++e)
                    if (overlaps(small_[e].box) && stop(small_[e].id)) return;
            }
        if (big_.empty()) return;
        // Boxes filed in every cell they overlap: each reported from the cell of the overlap's low corner only.
        for (std::int64_t k = low[2]; k <= high[2]; ++k)
            for (std::int64_t j = low[1]; j <= high[1]; ++j)
                for (std::int64_t i = low[0]; i <= high[0]; ++i) {
                    const auto cell = static_cast<std::size_t>(i + counts_[0] * (j + counts_[1] * k));
                    for (std::uint32_t e = big_start_[cell]; e < big_start_[cell + 1]; ++e) {
                        const Entry& b = big_[e];
                        if (b.id < first_big || !overlaps(b.box)) continue;
                        const auto ref = cell_of({std::max(box.low[0], static_cast<double>(b.box.low[0])),
                                                  std::max(box.low[1], static_cast<double>(b.box.low[1])),
                                                  std::max(box.low[2], static_cast<double>(b.box.low[2]))});
                        if (ref[0] == i && ref[1] == j && ref[2] == k && stop(b.id)) return;
                    }
                }
    }

    /// A filed box: single precision, rounded outward (CompactBox), next to its id.
    struct Entry {
        CompactBox box;
        std::uint32_t id;
    };
    static constexpr std::uint32_t big_bit = 1u << 31; ///< in where_: an entry of big_
    static float float_down(double x)
    {
        const auto f = static_cast<float>(x);
        return static_cast<double>(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
    }
    static float float_up(double x)
    {
        const auto f = static_cast<float>(x);
        return static_cast<double>(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
    }

    std::array<std::int64_t, 3> cell_of(const Vec3& p) const
    {
        std::array<std::int64_t, 3> c{};
        for (int a = 0; a < 3; ++a) {
            const double x = std::floor((p[a] - origin_[a]) / cell_mm_);
            c[a] = x < 0 ? 0 : x >= static_cast<double>(counts_[a] - 1) ? counts_[a] - 1 : static_cast<std::int64_t>(x);
        }
        return c;
    }

    Vec3 origin_{0, 0, 0};
    double cell_mm_ = 1;
    std::array<std::int64_t, 3> counts_{0, 0, 0}; ///< cells along each axis (0: nothing filed)
    std::vector<std::uint32_t> small_start_;      ///< per cell, its first small entry (one more for the end)
    std::vector<Entry> small_;                    ///< boxes filed once, in the cell of their low corner
    std::vector<std::uint32_t> big_start_;        ///< per cell, its first big entry (one more for the end)
    std::vector<Entry> big_;                      ///< boxes filed in every cell they overlap
    std::vector<std::uint32_t> where_; ///< per id: its entry in small_, or big_bit | one of its entries in big_
};

} // namespace tissuemesh::surface::detail

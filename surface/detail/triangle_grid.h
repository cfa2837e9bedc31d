// TriangleGrid: a uniform grid of cells over space, each listing the triangles whose bounding boxes
// overlap it; finds the triangles near a box in time proportional to the cells it covers.
#pragma once

#include <cstdint>
#include <vector>

#include "core/interface_complex.h"
#include "surface/detail/triangle_distance.h"

namespace tissuemesh::surface::detail {

struct Box3 {
    Vec3 low{0, 0, 0};
    Vec3 high{0, 0, 0};
};

Box3 bounding_box(const TriangleCorners& t, double margin = 0);
bool boxes_overlap(const Box3& a, const Box3& b);
/// A box in single precision, rounded outward (it holds the Box3 it was made from): half the memory,
/// for per-triangle boxes kept for quick rejection.
struct CompactBox {
    std::array<float, 3> low{0, 0, 0};
    std::array<float, 3> high{0, 0, 0};
};
CompactBox compact(const Box3& box);
inline bool boxes_overlap(const Box3& a, const CompactBox& b)
{
    for (int i = 0; i < 3; ++i)
        if (a.high[i] < b.low[i] || b.high[i] < a.low[i]) return false;
    return true;
}
/// The smallest box holding a and b.
Box3 box_union(const Box3& a, const Box3& b);

class TriangleGrid {
public:
    TriangleGrid() = default;
    /// A grid over `bounds` (points outside fall into the border cells) with cubic cells of about
    /// `cell_mm`, enlarged when needed to keep the number of cells below `max_cells`.
    TriangleGrid(const Box3& bounds, double cell_mm, std::size_t triangle_slots, std::size_t max_cells = 1u << 23);

    void insert(std::uint32_t t, const Box3& box);
    void erase(std::uint32_t t, const Box3& box);
    /// Triangles whose cells overlap `box`, each once, in no particular order (boxes not compared).
    void query(const Box3& box, std::vector<std::uint32_t>& out);
    /// Calls visit(t) for every triangle of the cells `box` overlaps, repeats included. Reads only.
    template <class Visit>
    void visit(const Box3& box, Visit visit) const
    {
        const auto low = cell_of(box.low), high = cell_of(box.high);
        for (std::int64_t k = low[2]; k <= high[2]; ++k)
            for (std::int64_t j = low[1]; j <= high[1]; ++j)
                for (std::int64_t i = low[0]; i <= high[0]; ++i)
                    for (const std::uint32_t t :
                         cells_[static_cast<std::size_t>(i + counts_[0] * (j + counts_[1] * k))])
                        visit(t);
    }
    double cell_mm() const { return cell_mm_; }

private:
    std::array<std::int64_t, 3> cell_of(const Vec3& p) const;
    template <class Visit>
    void for_cells(const Box3& box, Visit visit);

    Vec3 origin_{0, 0, 0};
    double cell_mm_ = 1;
    std::array<std::int64_t, 3> counts_{1, 1, 1};
    std::vector<std::vector<std::uint32_t>> cells_;
    std::vector<std::uint32_t> seen_; ///< per triangle slot: the last query that reported it
    std::uint32_t query_id_ = 0;
};

} // namespace tissuemesh::surface::detail

// BoxIndex: the all-pairs search of the surface checker asks each box for the overlapping boxes that come
// after it (visit_later); every overlapping pair must come out exactly once, as a brute-force search finds them.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <utility>

#include "surface/detail/box_index.h"

namespace tissuemesh {
namespace {

using surface::detail::Box3;
using surface::detail::BoxIndex;
using surface::detail::CompactBox;

/// Boxes with coordinates on a 1/64 grid (exact in single precision, so a box and its compact copy agree):
/// mostly small ones, one in twenty up to eight times larger (filed in every cell they overlap).
std::vector<Box3> random_boxes(std::size_t count, unsigned seed)
{
    std::mt19937 random(seed);
    std::uniform_int_distribution<int> where(0, 64 * 16), size(0, 64), big(0, 19);
    std::vector<Box3> boxes;
    for (std::size_t n = 0; n < count; ++n) {
        Box3 box;
        const int scale = big(random) == 0 ? 8 : 1;
        for (int a = 0; a < 3; ++a) {
            box.low[a] = where(random) / 64.0;
            box.high[a] = box.low[a] + scale * size(random) / 64.0;
        }
        boxes.push_back(box);
    }
    return boxes;
}

bool overlap(const Box3& a, const Box3& b)
{
    for (int i = 0; i < 3; ++i)
        if (a.high[i] < b.low[i] || b.high[i] < a.low[i]) return false;
    return true;
}

TEST(BoxIndex, VisitLaterReportsEveryOverlappingPairOnce)
{
    for (const unsigned seed : {1u, 2u, 3u}) {
        const std::vector<Box3> boxes = random_boxes(3000, seed);
        std::vector<CompactBox> compact_boxes;
        std::vector<std::uint32_t> ids;
        for (std::uint32_t id = 0; id < boxes.size(); ++id) {
            compact_boxes.push_back(surface::detail::compact(boxes[id]));
            ids.push_back(id);
        }
        const BoxIndex index(compact_boxes, ids);
        std::set<std::pair<std::uint32_t, std::uint32_t>> expected;
        for (std::uint32_t a = 0; a < boxes.size(); ++a)
            for (std::uint32_t b = a + 1; b < boxes.size(); ++b)
                if (overlap(boxes[a], boxes[b])) expected.insert({a, b});
        std::vector<std::pair<std::uint32_t, std::uint32_t>> found;
        for (std::uint32_t id = 0; id < boxes.size(); ++id)
            index.visit_later(id, boxes[id], [&](std::uint32_t other) {
                found.emplace_back(std::min(id, other), std::max(id, other));
            });
        std::sort(found.begin(), found.end());
        EXPECT_EQ(std::adjacent_find(found.begin(), found.end()), found.end())
            << "a pair reported twice, seed " << seed;
        EXPECT_EQ(std::set(found.begin(), found.end()), expected) << "seed " << seed;
        EXPECT_GT(expected.size(), boxes.size()) << "the test needs many overlaps";
    }
}

} // namespace
} // namespace tissuemesh

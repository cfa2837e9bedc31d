// detail::exact_side(): the side of a plane a tet's vertex lies on, exact where doubles round wrong.
// tetrahedralize() labels each tet by it (the opposite vertex against the interface triangle's plane) and
// orients tets by it; the centroid tested in doubles it replaces could put a nearly flat tet on the wrong side.
#include <gtest/gtest.h>

#include "volume/detail/tetgen_adapter.h"

namespace tissuemesh::volume::detail {
namespace {

TEST(ExactSide, PlainCasesFollowTheRightHandNormal)
{
    const std::array<double, 3> a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
    EXPECT_EQ(exact_side(a, b, c, {0.2, 0.2, 1}), 1);
    EXPECT_EQ(exact_side(a, b, c, {0.2, 0.2, -1}), -1);
    EXPECT_EQ(exact_side(a, c, b, {0.2, 0.2, 1}), -1);
    EXPECT_EQ(exact_side(a, b, c, {5, -3, 0}), 0);
}

// Four nearly coplanar points at head coordinates (mm), found by comparing the double
// expression dot(d - a, cross(b - a, c - a)) with rational arithmetic: the doubles give -8.9e-16 mm^3, the exact
// value is +1.5e-16 mm^3. The regression: a flat tet between close interfaces took the tissue across its face.
TEST(ExactSide, NearlyCoplanarPointsWhereDoublesGiveTheWrongSign)
{
    const std::array<double, 3> a{37.2, 123.3, 102.6}, b{38.86, 125.76, 103.6}, c{35.54, 124.54, 104.15};
    const std::array<double, 3> d{35.93712232408253, 124.39210928430977, 103.88171326288162};
    EXPECT_EQ(exact_side(a, b, c, d), 1);
    EXPECT_EQ(exact_side(b, a, c, d), -1);
    EXPECT_EQ(exact_side(a, b, c, a), 0);
}

} // namespace
} // namespace tissuemesh::volume::detail

// LocalEditor's vertex moves: a move that ends in a valid place may still carry the vertex through the surface.
// On the 1 mm usc19-5 head, remeshing turned a two-voxel air pocket in the skull (decimated to a tetrahedron of
// four triangles) inside out by small moves, none of them tilting a triangle much or making an intersection;
// tm-check-surface passed it and TetGen's tets then disagreed on their tissue around it.
#include <cmath>
#include <map>
#include <utility>

#include <gtest/gtest.h>

#include "surface/check_complex.h"
#include "surface/detail/edge_fan.h"
#include "surface/detail/local_editor.h"

namespace tissuemesh {
namespace {

using surface::detail::LocalEditor;

/// Tissue 1 in a tetrahedron (apex over the base (0, 0, 0), (2, 0, 0), (0, 2, 0) in z = 0), the background 0
/// around it, its faces cut into 40 triangles (the base into 25 by a 5 x 5 grid, each side into a fan of 5) so
/// that the small-piece rule (at most 24 triangles: test_small_pieces.cpp) leaves it alone: the path rule alone
/// must keep it right side out. Returns the apex's index in `apex`.
InterfaceComplex pocket(std::uint32_t& apex)
{
    constexpr int n = 5;
    InterfaceComplex complex;
    std::map<std::pair<int, int>, std::uint32_t> grid;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i + j <= n; ++i) {
            grid[{i, j}] = static_cast<std::uint32_t>(complex.vertices.size());
            complex.vertices.push_back({2.0 * i / n, 2.0 * j / n, 0});
        }
    apex = static_cast<std::uint32_t>(complex.vertices.size());
    complex.vertices.push_back({0.5, 0.5, 1});
    const auto p = [&](int i, int j) { return grid.at({i, j}); };
    const LabelPair sides{1, 0}; // normals outwards: from tissue 1 to the background
    for (int j = 0; j < n; ++j)
        for (int i = 0; i + j < n; ++i) {
            complex.add_triangle({p(i, j), p(i, j + 1), p(i + 1, j)}, sides); // base: normals down
            if (i + j < n - 1) complex.add_triangle({p(i + 1, j), p(i, j + 1), p(i + 1, j + 1)}, sides);
        }
    for (int k = 0; k < n; ++k) {
        complex.add_triangle({p(k, 0), p(k + 1, 0), apex}, sides);
        complex.add_triangle({p(0, k + 1), p(0, k), apex}, sides);
        complex.add_triangle({p(n - k, k), p(n - k - 1, k + 1), apex}, sides);
    }
    return complex;
}

double signed_volume(const std::array<Vec3, 4>& p) { return dot(cross(p[1] - p[0], p[2] - p[0]), p[3] - p[0]) / 6; }

TEST(LocalEditor, AMoveThroughTheOppositeFaceIsRefusedThoughEveryStepLooksFine)
{
    std::uint32_t apex = 0;
    const InterfaceComplex complex = pocket(apex);
    ASSERT_EQ(complex.triangles.size(), 40u);
    ASSERT_TRUE(surface::check_complex(complex).ok());
    LocalEditor editor(complex, {.min_angle_deg = 1, .max_tilt_deg = 45, .min_gap_mm = 0}, 2.0);
    // Down towards the base: each step tilts the side triangles by 16-23 degrees and is kept.
    for (const double z : {0.5, 0.2, 0.05}) EXPECT_TRUE(editor.try_move(apex, {0.5, 0.5, z})) << z;
    // Through the base: the side triangles tilt by 11 degrees and meet nothing, but the pocket would be inside out.
    EXPECT_FALSE(editor.try_move(apex, {0.5, 0.5, -0.05}));
    EXPECT_DOUBLE_EQ(editor.position(apex)[2], 0.05);
    EXPECT_GT(signed_volume({editor.position(0), editor.position(5), editor.position(20), editor.position(apex)}),
              0); // the corners
    EXPECT_TRUE(surface::check_complex(editor.result()).ok());
    // Beside the base (not through it) the same depth would make triangles cross: refused as before.
    EXPECT_FALSE(editor.try_move(apex, {2.5, 2.5, -0.05}));
    // Back up: allowed.
    EXPECT_TRUE(editor.try_move(apex, {0.5, 0.5, 0.3}));
}

// The sector rule: the pocket's tissue fills the angle between its base and its sides at the base's edges (the
// apex over (0.5, 0.5): atan(z / 0.5) at the edges on the axes, atan(z / 0.707) at the third), which bounds the
// dihedral angles of every tet tm-tetra can put there. A move may not close it below the limit, unless it leaves
// it wider than it was.
TEST(LocalEditor, AMoveThatClosesATissueSectorBelowTheLimitIsRefused)
{
    constexpr double pi = 3.14159265358979323846;
    std::uint32_t apex = 0;
    const InterfaceComplex complex = pocket(apex);
    const surface::detail::LocalLimits without{.min_angle_deg = 1, .max_tilt_deg = 45, .min_gap_mm = 0};
    surface::detail::LocalLimits with = without;
    with.min_sector_deg = 15;
    LocalEditor editor(complex, with, 2.0);
    EXPECT_TRUE(editor.try_move(apex, {0.5, 0.5, 0.2})); // 21.8 and 15.8 degrees
    EXPECT_NEAR(surface::detail::smallest_sector_deg(editor.result()), std::atan(0.2 / std::sqrt(0.5)) * 180 / pi,
                1e-9);
    EXPECT_FALSE(editor.try_move(apex, {0.5, 0.5, 0.1})); // 8.0 degrees at the third edge
    EXPECT_DOUBLE_EQ(editor.position(apex)[2], 0.2);
    // Without the rule the same move is made; with it again, a sector under the limit may open but not close.
    editor.set_limits(without);
    EXPECT_TRUE(editor.try_move(apex, {0.5, 0.5, 0.1}));
    editor.set_limits(with);
    EXPECT_TRUE(editor.try_move(apex, {0.5, 0.5, 0.12}));
    EXPECT_FALSE(editor.try_move(apex, {0.5, 0.5, 0.11}));
    EXPECT_TRUE(surface::check_complex(editor.result()).ok());
}

// The same pocket holding the background inside tissue 1: tm-tetra meshes background that tissues enclose, so the
// cavity's sectors bound its tets as a tissue's do, and they count (on the liver sample the worst tets were in such
// cavities, 6 degrees, while every tissue sector was 15 or more).
TEST(LocalEditor, ABackgroundCavitysSectorsCountAsATissues)
{
    constexpr double pi = 3.14159265358979323846;
    std::uint32_t apex = 0;
    InterfaceComplex cavity = pocket(apex);
    for (LabelPair& side : cavity.sides) std::swap(side.from, side.to);
    cavity.vertices[apex] = {0.5, 0.5, 0.2};
    EXPECT_NEAR(surface::detail::smallest_sector_deg(cavity), std::atan(0.2 / std::sqrt(0.5)) * 180 / pi, 1e-9);
    surface::detail::LocalLimits with{.min_angle_deg = 1, .max_tilt_deg = 45, .min_gap_mm = 0};
    with.min_sector_deg = 15;
    LocalEditor editor(cavity, with, 2.0);
    EXPECT_FALSE(editor.try_move(apex, {0.5, 0.5, 0.1})); // 8.0 degrees at the third edge, in the cavity
    EXPECT_TRUE(editor.try_move(apex, {0.5, 0.5, 0.3}));
}

} // namespace
} // namespace tissuemesh

// LocalEditor's vertex moves: a move that ends in a valid place may still carry the vertex through the surface.
// On the 1 mm usc19-5 head, remeshing turned a two-voxel air pocket in the skull (decimated to a tetrahedron of
// four triangles) inside out by small moves, none of them tilting a triangle much or making an intersection;
// tm-check-surface passed it and TetGen's tets then disagreed on their tissue around it.
#include <gtest/gtest.h>

#include "surface/check_complex.h"
#include "surface/detail/local_editor.h"

namespace tissuemesh {
namespace {

using surface::detail::LocalEditor;

/// Tissue 1 in a tetrahedron (apex 3 over the base 0, 1, 2 in z = 0), the background 0 around it.
InterfaceComplex pocket()
{
    InterfaceComplex complex;
    complex.vertices = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, 1}};
    for (const Triangle& t : {Triangle{0, 2, 1}, Triangle{0, 1, 3}, Triangle{1, 2, 3}, Triangle{2, 0, 3}})
        complex.add_triangle(t, {1, 0});  // normals outwards: from tissue 1 to the background
    return complex;
}

double signed_volume(const std::array<Vec3, 4>& p)
{
    return dot(cross(p[1] - p[0], p[2] - p[0]), p[3] - p[0]) / 6;
}

TEST(LocalEditor, AMoveThroughTheOppositeFaceIsRefusedThoughEveryStepLooksFine)
{
    ASSERT_TRUE(surface::check_complex(pocket()).ok());
    LocalEditor editor(pocket(), {.min_angle_deg = 5, .max_tilt_deg = 45, .min_gap_mm = 0}, 2.0);
    // Down towards the base: each step tilts the side triangles by 16-23 degrees and is kept.
    for (const double z : {0.5, 0.2, 0.05}) EXPECT_TRUE(editor.try_move(3, {0.5, 0.5, z})) << z;
    // Through the base: the side triangles tilt by 11 degrees and meet nothing, but the pocket would be inside out.
    EXPECT_FALSE(editor.try_move(3, {0.5, 0.5, -0.05}));
    EXPECT_DOUBLE_EQ(editor.position(3)[2], 0.05);
    EXPECT_GT(signed_volume({editor.position(0), editor.position(1), editor.position(2), editor.position(3)}), 0);
    EXPECT_TRUE(surface::check_complex(editor.result()).ok());
    // Beside the base (not through it) the same depth would make triangles cross: refused as before.
    EXPECT_FALSE(editor.try_move(3, {2.5, 2.5, -0.05}));
    // Back up: allowed.
    EXPECT_TRUE(editor.try_move(3, {0.5, 0.5, 0.3}));
}

} // namespace
} // namespace tissuemesh

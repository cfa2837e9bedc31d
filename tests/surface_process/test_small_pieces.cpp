// Small closed pieces of a tissue keep a shape TetGen can fill. On the 3 mm torso, decimation shrank a pocket of
// the body between two organs (bounded by two tissue pairs, so the one-pair rule of the time did not see it)
// to a flat tetrahedron: TetGen's tet inside it had a smallest dihedral angle of 0.012 degrees, and no
// improvement can mend a tet whose four faces are all interfaces. The usc19-5 head had the same in a CSF speck.
#include <cmath>

#include <gtest/gtest.h>

#include "surface/check_complex.h"
#include "surface/detail/local_editor.h"
#include "surface/extract_surface_nets.h"

namespace tissuemesh {
namespace {

using surface::detail::LocalEditor;

/// Tissue 1 above z = 3 voxels and tissue 2 below in a 6 x 6 x 6 block, and two voxels of tissue 3 across their
/// interface: a small piece bounded by the pairs 3|1 and 3|2.
InterfaceComplex straddling_pocket()
{
    LabelImage image({6, 6, 6}, {1, 1, 1});
    for (std::size_t k = 0; k < 6; ++k)
        for (std::size_t j = 0; j < 6; ++j)
            for (std::size_t i = 0; i < 6; ++i) image.at(i, j, k) = k >= 3 ? 1 : 2;
    image.at(2, 2, 2) = image.at(2, 2, 3) = 3;
    return surface::extract_surface_nets(image);
}

struct Shape {
    double volume = 0, area = 0;
    double fatness() const { return std::abs(volume) / std::pow(area, 1.5); }
};

/// Volume (tissue 3 inside positive) and area of tissue 3's triangles, with vertex v at p.
Shape pocket_shape(const LocalEditor& editor, const std::vector<std::uint32_t>& triangles, std::uint32_t v,
                   const Vec3& p)
{
    Shape shape;
    for (const std::uint32_t t : triangles) {
        std::array<Vec3, 3> c;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t x = editor.triangle(t)[k];
            c[k] = x == v ? p : editor.position(x);
        }
        const double sign = editor.side(t).from == 3 ? 1 : -1;
        shape.volume += sign * dot(cross(c[0], c[1]), c[2]) / 6;
        shape.area += norm(cross(c[1] - c[0], c[2] - c[0])) / 2;
    }
    return shape;
}

TEST(SmallPieces, APocketBetweenTwoTissuesIsNotFlattened)
{
    const InterfaceComplex complex = straddling_pocket();
    ASSERT_TRUE(surface::check_complex(complex).ok());
    LocalEditor editor(complex, {.min_angle_deg = 0.5, .max_tilt_deg = 89, .min_gap_mm = 0}, 2.0);
    std::vector<std::uint32_t> pocket;
    for (std::uint32_t t = 0; t < complex.triangles.size(); ++t)
        if (complex.sides[t].from == 3 || complex.sides[t].to == 3) pocket.push_back(t);
    bool two_pairs = false;
    for (const std::uint32_t t : pocket) two_pairs |= !(complex.sides[t] == complex.sides[pocket[0]]);
    ASSERT_TRUE(two_pairs);
    ASSERT_LE(pocket.size(), 24u);
    // Flatten the pocket: every vertex of it in turn towards the pocket's middle plane z = 3, in steps.
    std::size_t accepted = 0, refused_thin = 0;
    for (int step = 1; step <= 8; ++step)
        for (const std::uint32_t t : pocket)
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t v = editor.triangle(t)[k];
                const Vec3 now = editor.position(v);
                const Vec3 to{now[0], now[1], now[2] + (3 - now[2]) * 0.4};
                const double before = pocket_shape(editor, pocket, v, now).fatness();
                const Shape after = pocket_shape(editor, pocket, v, to);
                const bool thin = after.fatness() < 0.02 && after.fatness() < before;
                if (editor.try_move(v, to)) {
                    ++accepted;
                    EXPECT_FALSE(thin) << "vertex " << v << " step " << step << ": fatness " << before << " -> "
                                       << after.fatness();
                } else {
                    refused_thin += thin;
                }
            }
    EXPECT_GT(accepted, 0u);
    EXPECT_GT(refused_thin, 0u);
    const std::uint32_t any = editor.triangle(pocket[0])[0];
    const Shape final_shape = pocket_shape(editor, pocket, any, editor.position(any));
    EXPECT_GE(final_shape.fatness(), 0.02 - 1e-12);
    EXPECT_GT(final_shape.volume, 0);
    EXPECT_TRUE(surface::check_complex(editor.result()).ok());
}

} // namespace
} // namespace tissuemesh

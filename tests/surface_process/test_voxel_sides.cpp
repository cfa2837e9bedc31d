// VoxelSides and remesh(voxel_image): an edit that would carry a voxel centre next to another label across the surface
// is caught; remeshing with the image keeps more voxel centres on their own tissue's side.
#include <gtest/gtest.h>

#include <iostream>
#include <limits>
#include <vector>

#include "image/phantom.h"
#include "surface/check_complex.h"
#include "surface/decimate.h"
#include "surface/detail/triangle_distance.h"
#include "surface/detail/voxel_sides.h"
#include "surface/extract_surface_nets.h"
#include "surface/remesh.h"

namespace tissuemesh {
namespace {

using surface::detail::TriangleCorners;

/// A fan of triangles around `apex` over a square link of half-width `half` in the plane z = `z` around (cx, cy).
std::vector<TriangleCorners> fan(const Vec3& apex, double cx, double cy, double z, double half)
{
    const std::vector<Vec3> link{
        {cx - half, cy - half, z}, {cx + half, cy - half, z}, {cx + half, cy + half, z}, {cx - half, cy + half, z}};
    std::vector<TriangleCorners> triangles;
    for (std::size_t i = 0; i < link.size(); ++i) triangles.push_back({apex, link[i], link[(i + 1) % link.size()]});
    return triangles;
}

TEST(VoxelSides, AMoveAcrossAVoxelCentreIsCaughtAndAShorterOneIsNot)
{
    // Tissue 1 below z = 2.5 mm, tissue 2 above: the centres at z = 2 and z = 3 are next to the other label.
    LabelImage image({6, 6, 6}, {1, 1, 1}, {0, 0, 0}, identity_matrix(), 1);
    for (std::size_t k = 3; k < 6; ++k)
        for (std::size_t j = 0; j < 6; ++j)
            for (std::size_t i = 0; i < 6; ++i) image.at(i, j, k) = 2;
    const surface::detail::VoxelSides sides(image);
    const std::vector<TriangleCorners> flat = fan({2.5, 2.5, 2.5}, 2.5, 2.5, 2.5, 1.5);
    // The apex 0.9 mm up: at (2, 2) and (3, 3), 0.5 mm from it, the cone reaches z = 3.1, past the centres at z = 3.
    EXPECT_TRUE(sides.carries_a_centre(flat, fan({2.5, 2.5, 3.4}, 2.5, 2.5, 2.5, 1.5)));
    // 0.4 mm up it reaches z = 2.77 there: no centre crossed.
    EXPECT_FALSE(sides.carries_a_centre(flat, fan({2.5, 2.5, 2.9}, 2.5, 2.5, 2.5, 1.5)));
    // Down across the centres at z = 2, and sideways within the plane (nothing swept).
    EXPECT_TRUE(sides.carries_a_centre(flat, fan({2.5, 2.5, 1.6}, 2.5, 2.5, 2.5, 1.5)));
    EXPECT_FALSE(sides.carries_a_centre(flat, fan({2.9, 2.2, 2.5}, 2.5, 2.5, 2.5, 1.5)));
    // No centre next to another label: nothing to carry.
    const LabelImage uniform({6, 6, 6}, {1, 1, 1}, {0, 0, 0}, identity_matrix(), 1);
    EXPECT_FALSE(surface::detail::VoxelSides(uniform).carries_a_centre(flat, fan({2.5, 2.5, 3.4}, 2.5, 2.5, 2.5, 1.5)));
}

/// The voxel centres next to another label (not background) that `complex` puts outside their own tissue: a ray
/// from the centre crosses the triangles with that tissue on a side an even number of times.
std::size_t centres_on_the_wrong_side(const LabelImage& image, const InterfaceComplex& complex)
{
    const Vec3 d = (1 / norm(Vec3{0.5773, 0.5801, 0.5749})) * Vec3{0.5773, 0.5801, 0.5749};
    const auto crosses = [&](const Vec3& o, const Triangle& t) {
        return surface::detail::ray_meets_triangle(
                   o, d, {complex.vertices[t[0]], complex.vertices[t[1]], complex.vertices[t[2]]},
                   std::numeric_limits<double>::infinity())
            .has_value();
    };
    std::size_t wrong = 0;
    const Dims& n = image.dims();
    for (std::size_t k = 1; k + 1 < n[2]; ++k)
        for (std::size_t j = 1; j + 1 < n[1]; ++j)
            for (std::size_t i = 1; i + 1 < n[0]; ++i) {
                const Label l = image.at(i, j, k);
                if (l == 0) continue;
                if (image.at(i - 1, j, k) == l && image.at(i + 1, j, k) == l && image.at(i, j - 1, k) == l &&
                    image.at(i, j + 1, k) == l && image.at(i, j, k - 1) == l && image.at(i, j, k + 1) == l)
                    continue;
                const Vec3 centre =
                    image.index_to_world({static_cast<double>(i), static_cast<double>(j), static_cast<double>(k)});
                bool inside = false;
                for (std::size_t t = 0; t < complex.triangle_count(); ++t)
                    if (complex.sides[t].from == l || complex.sides[t].to == l)
                        inside ^= crosses(centre, complex.triangles[t]);
                wrong += !inside;
            }
    return wrong;
}

TEST(RemeshVoxelSides, AOneVoxelShellKeepsMoreOfItsVoxels)
{
    const image::Phantom phantom = image::make_phantom("thin", {.voxel_mm = 2.0});
    InterfaceComplex extracted = surface::extract_surface_nets(phantom.image, {.priority = {{1, 1}}});
    surface::decimate(extracted, {.max_distance_mm = 0.5, .max_edge_mm = 8, .max_normal_change_deg = 45});
    InterfaceComplex plain = extracted, kept = extracted;
    const surface::RemeshReport without = surface::remesh(plain, {.target_edge_mm = 6});
    const surface::RemeshReport with = surface::remesh(kept, {.target_edge_mm = 6, .voxel_image = &phantom.image});
    EXPECT_TRUE(surface::check_complex(kept).ok());
    EXPECT_GT(with.refused_by_voxels, 0u);
    EXPECT_EQ(without.refused_by_voxels, 0u);
    const std::size_t before = centres_on_the_wrong_side(phantom.image, extracted);
    const std::size_t wrong_without = centres_on_the_wrong_side(phantom.image, plain);
    const std::size_t wrong_with = centres_on_the_wrong_side(phantom.image, kept);
    std::cout << "[ figures  ] thin 2 mm, voxel centres next to another label on the wrong side: decimated " << before
              << ", remeshed " << wrong_without << ", remeshed keeping the voxels' sides " << wrong_with << " ("
              << with.refused_by_voxels << " edits refused; " << without.triangles_after << " and "
              << with.triangles_after << " triangles)\n";
    EXPECT_LT(wrong_with, wrong_without);
}

} // namespace
} // namespace tissuemesh

// Issue 4: a layer half a voxel thick, where decimation alone would make its two surfaces cross. Each
// surface decimated on its own (as patch-by-patch tools do) does cross the other; decimate() on the
// complex refuses those collapses and keeps the layer's thickness.
#include <gtest/gtest.h>

#include <iostream>

#include "surface/check_complex.h"
#include "surface/decimate.h"
#include "surface/detail/triangle_distance.h"
#include "tests/support/complexes.h"

namespace tissuemesh {
namespace {

constexpr double voxel_mm = 1.0;
constexpr double outer_mm = 20.0, inner_mm = outer_mm - 0.5 * voxel_mm;

/// Appends `part` to `complex` with every triangle separating `pair`.
void append(InterfaceComplex& complex, const InterfaceComplex& part, LabelPair pair)
{
    const auto base = static_cast<std::uint32_t>(complex.vertices.size());
    complex.vertices.insert(complex.vertices.end(), part.vertices.begin(), part.vertices.end());
    for (const Triangle& t : part.triangles) complex.add_triangle({base + t[0], base + t[1], base + t[2]}, pair);
}

/// Smallest distance from a vertex of the inner surface (2|1) to a triangle of the outer one (1|0) and back.
double thinnest(const InterfaceComplex& complex)
{
    double d = 1e300;
    for (std::size_t a = 0; a < complex.triangles.size(); ++a)
        for (std::size_t b = 0; b < complex.triangles.size(); ++b) {
            if (complex.sides[a].from != 1 || complex.sides[b].from != 2) continue;
            const Triangle& ta = complex.triangles[a];
            const Triangle& tb = complex.triangles[b];
            const surface::detail::TriangleCorners ca{complex.vertices[ta[0]], complex.vertices[ta[1]],
                                                      complex.vertices[ta[2]]};
            const surface::detail::TriangleCorners cb{complex.vertices[tb[0]], complex.vertices[tb[1]],
                                                      complex.vertices[tb[2]]};
            for (int k = 0; k < 3; ++k) {
                d = std::min(d, distance(cb[k], surface::detail::closest_point_on_triangle(cb[k], ca)));
                d = std::min(d, distance(ca[k], surface::detail::closest_point_on_triangle(ca[k], cb)));
            }
        }
    return d;
}

TEST(DecimateHalfVoxelLayer, AloneItWouldCrossTogetherItRefuses)
{
    // The bound lets a lone sphere's faces sink up to 1.5 mm inside its vertices: three times the layer.
    const surface::DecimateOptions options{.max_distance_mm = 1.5, .max_normal_change_deg = 30, .min_gap_mm = 0.1};
    const InterfaceComplex outer = testing::icosphere(4, outer_mm, {0, 0, 0});
    const InterfaceComplex inner = testing::icosphere(4, inner_mm, {0, 0, 0});

    InterfaceComplex outer_alone = outer, inner_alone = inner;
    surface::decimate(outer_alone, options);
    surface::decimate(inner_alone, options);
    InterfaceComplex separately;
    append(separately, outer_alone, {1, 0});
    append(separately, inner_alone, {2, 1});
    const surface::CheckReport crossed = surface::check_complex(separately);

    InterfaceComplex together;
    append(together, outer, {1, 0});
    append(together, inner, {2, 1});
    ASSERT_TRUE(surface::check_complex(together).ok());
    const surface::DecimateReport report = surface::decimate(together, options);
    const surface::CheckReport after = surface::check_complex(together);
    std::cout << "[ figures  ] layer 0.5 voxel thick, 2 x " << outer.triangle_count() << " triangles: decimated "
              << "separately -> " << separately.triangle_count() << " triangles, "
              << crossed.count(surface::DefectKind::patch_intersection) << " crossing pairs; together -> "
              << together.triangle_count() << " triangles, refused " << report.refused_intersection
              << " collapses as crossing and " << report.refused_gap << " as closing the gap; thinnest "
              << thinnest(together) << " mm\n";
    EXPECT_GT(crossed.count(surface::DefectKind::patch_intersection), 0u) << "decimation alone would cross";
    EXPECT_TRUE(after.ok()) << (after.first_error() ? after.first_error()->description : "");
    EXPECT_GT(report.refused_intersection + report.refused_gap, 0u);
    EXPECT_LT(together.triangle_count(), outer.triangle_count()) << "it still decimates, over 2x";
    EXPECT_GE(thinnest(together), options.min_gap_mm) << "the layer keeps a thickness";
    EXPECT_EQ(after.tissues.at(1).components, 2u);
}

} // namespace
} // namespace tissuemesh

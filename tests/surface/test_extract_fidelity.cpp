// How close the midpoint dual surface lies to the exact geometry it was voxelised from.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>
#include <limits>
#include <numbers>

#include "image/phantom.h"
#include "surface/check_complex.h"
#include "surface/extract_interfaces.h"
#include "tests/support/phantom_distance.h"
#include "tests/surface/complex_checks.h"

namespace tissuemesh {
namespace {

using surface::extract_interfaces;

using testing::DistanceFigures;
using testing::phantom_distances;

TEST(ExtractFidelity, SphereOfRadius30mmAt1mm)
{
    // Voxel centres within 30 mm of the centre are tissue 1. Every vertex is the midpoint of a
    // Freudenthal edge with one end inside and one outside (a 2-label image has no centroids), and the
    // longest such edge is the body diagonal (sqrt(3) voxels), so no vertex is further than
    // sqrt(3)/2 = 0.866 voxel from the sphere; on average much less.
    const int n = 65;
    const double c = 32, radius = 30;
    LabelImage image({n, n, n}, {1, 1, 1});
    for (std::size_t k = 0; k < image.dims()[2]; ++k)
        for (std::size_t j = 0; j < image.dims()[1]; ++j)
            for (std::size_t i = 0; i < image.dims()[0]; ++i) {
                const Vec3 d{static_cast<double>(i) - c, static_cast<double>(j) - c, static_cast<double>(k) - c};
                image.at(i, j, k) = norm(d) <= radius ? 1 : 0;
            }
    const InterfaceComplex complex = extract_interfaces(image);
    DistanceFigures figures;
    for (const Vec3& v : complex.vertices) {
        const double error = std::abs(norm(v - Vec3{c, c, c}) - radius);
        figures.max_voxels = std::max(figures.max_voxels, error);
        figures.mean_voxels += error;
    }
    figures.mean_voxels /= static_cast<double>(complex.vertices.size());
    std::cout << "[ figures  ] sphere r=30 at 1 mm: " << complex.triangle_count() << " triangles, vertex distance max "
              << figures.max_voxels << " mean " << figures.mean_voxels << " voxel\n";
    EXPECT_LE(figures.max_voxels, 0.87);
    EXPECT_LT(figures.mean_voxels, 0.35);
    // Volume: the exact ball is 4/3 pi 30^3 = 113 097 mm^3; voxel count and dual surface both approximate
    // it. The dual surface cuts voxel corners, so it encloses a little less than the voxels: measured.
    const testing::TissueSurfaceFacts facts = testing::tissue_facts(complex, 1);
    const double voxels = static_cast<double>(count_labels(image).at(1));
    const double exact = 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
    std::cout << "[ figures  ] volume: surface " << facts.volume_mm3 << ", voxels " << voxels << ", exact " << exact
              << " mm^3\n";
    EXPECT_NEAR(facts.volume_mm3, exact, 0.01 * exact) << "1% of the ball at 30 voxels radius";
    EXPECT_NEAR(voxels, exact, 0.001 * exact);
}

void check_spheres4(double voxel_mm)
{
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = voxel_mm});
    const InterfaceComplex complex = extract_interfaces(phantom.image);
    const surface::CheckReport report = surface::check_complex(complex);
    EXPECT_TRUE(report.ok()) << (report.first_error() ? report.first_error()->description : "");
    for (const Label tissue : phantom.geometry.tissues()) {
        const testing::TissueSurfaceFacts facts = testing::tissue_facts(complex, tissue);
        EXPECT_EQ(facts.bad_edges, 0u) << "tissue " << tissue;
        // Balls have one surface, shells two, unless sampling breaks a thin shell (CSF is 2 mm thick):
        // then the voxels decide, under the Freudenthal 14-neighbourhood.
        const std::size_t expected = testing::voxel_components(phantom.image, tissue, 0, false) +
                                     testing::voxel_components(phantom.image, tissue, 0, true) - 1;
        EXPECT_EQ(facts.components, expected) << "tissue " << tissue;
        if (voxel_mm <= 1.0) {
            EXPECT_EQ(facts.components, tissue == 4 ? 1u : 2u);
        }
        const double exact = phantom.geometry.volume_mm3(tissue);
        std::cout << "[ figures  ] spheres4 at " << voxel_mm << " mm, tissue " << tissue << ": volume "
                  << facts.volume_mm3 << " exact " << exact << " (" << 100 * (facts.volume_mm3 / exact - 1) << "%)\n";
        // Shells 2 mm thick (CSF: 78..80 mm) are 1-2 voxels at 2 mm: their volume is off by the
        // partial-voxel layer on each side; 8% holds for every tissue at 1 and 2 mm (measured: see above).
        EXPECT_NEAR(facts.volume_mm3, exact, 0.08 * exact) << "tissue " << tissue;
    }
    const DistanceFigures figures = phantom_distances(phantom, complex);
    std::cout << "[ figures  ] spheres4 at " << voxel_mm << " mm: " << complex.triangle_count()
              << " triangles, vertex distance to the exact interface max " << figures.max_voxels << " mean "
              << figures.mean_voxels << " voxel\n";
    // Edge midpoints are within sqrt(3)/2 voxel of the interface their edge crosses; centroids (where 3
    // tissues share a tetrahedron, in the thin CSF) within the tetrahedron's diameter, sqrt(3) voxels.
    EXPECT_LE(figures.max_voxels, std::sqrt(3.0));
    EXPECT_LT(figures.mean_voxels, 0.35);
}

TEST(ExtractFidelity, Spheres4At2mm) { check_spheres4(2.0); }

TEST(ExtractFidelity, LongSpheres4At1mm) { check_spheres4(1.0); }

} // namespace
} // namespace tissuemesh

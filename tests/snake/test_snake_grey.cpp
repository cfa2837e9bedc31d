// Snakes on a grey-level image: the CT skull of data/samples/skull_2.9.inr at its iso value 2.9.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "io/read_grey_image.h"
#include "surface/check_complex.h"
#include "surface/snake.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

/// Distance (mm) from each vertex to the iso-surface of the unsmoothed trilinear field, estimated to first
/// order as |f - iso| / |grad f| (exact for a linear field; the snake's own field here is that same one).
struct IsoDistances {
    double mean_voxels = 0;
    double max_voxels = 0;
    double fraction_under_half_voxel = 0;
};

IsoDistances iso_distances(const InterfaceComplex& complex, const surface::PotentialField& field, double voxel_mm)
{
    IsoDistances d;
    std::size_t under = 0;
    for (const Vec3& p : complex.vertices) {
        const double g = norm(field.gradient(p));
        const double distance = g > 0 ? std::abs(field.value(p)) / g : 1e9;
        d.mean_voxels += distance / voxel_mm;
        d.max_voxels = std::max(d.max_voxels, distance / voxel_mm);
        if (distance < 0.5 * voxel_mm) ++under;
    }
    const double n = static_cast<double>(complex.vertices.size());
    d.mean_voxels /= n;
    d.fraction_under_half_voxel = static_cast<double>(under) / n;
    return d;
}

TEST(SnakeGrey, SkullAtIso29IsClosedAndOnTheIsoSurface)
{
    const io::GreyImage grey = io::read_grey_image(testing::data_path("samples/skull_2.9.inr"));
    const std::vector<surface::SnakeTarget> targets{
        {{1, 0}, surface::grey_potential(grey.grid, grey.values, 2.9, 0.0)}};
    const double voxel = targets[0].field.smallest_spacing_mm();
    InterfaceComplex complex = surface::bounding_ellipsoids(targets, 1.15, 2 * voxel);
    const surface::SnakeReport report = surface::evolve_snakes(complex, targets);
    const IsoDistances d = iso_distances(complex, targets[0].field, voxel);
    std::cout << "[ figures  ] skull_2.9.inr at 2.9: " << report.iterations << " iterations ("
              << (report.converged ? "converged" : "cap") << "), " << report.triangles << " triangles, "
              << report.refused_moves << " refused; distance to the iso-surface mean " << d.mean_voxels << " max "
              << d.max_voxels << " voxel, " << 100 * d.fraction_under_half_voxel << "% under 0.5 voxel\n";
    const surface::CheckReport check = surface::check_complex(complex);
    EXPECT_TRUE(check.ok()) << (check.first_error() ? check.first_error()->description : "");
    EXPECT_TRUE(check.tissues.at(1).closed);
    EXPECT_LT(d.mean_voxels, 0.5);
}

} // namespace
} // namespace tissuemesh

// Snakes on a grey-level image: the CT skull of data/samples/skull_2.9.inr at its iso value 2.9.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "io/read_grey_image.h"
#include "surface/check_complex.h"
#include "surface/snake.h"
#include "tests/snake/iso_surface_points.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

struct IsoDistances {
    double mean_voxels = 0;
    double max_voxels = 0;
    double fraction_under_half_voxel = 0;
};

/// Distances of the vertices to the iso-surface of the unsmoothed trilinear field (upper bounds, see
/// IsoSurfacePoints; 4 sample lines per voxel, so at most about 0.2 voxel too large), in voxels.
IsoDistances iso_distances(const InterfaceComplex& complex, const surface::PotentialField& field)
{
    const double voxel = field.smallest_spacing_mm();
    const testing::IsoSurfacePoints samples(field, 4);
    IsoDistances d;
    std::size_t under = 0;
    for (const Vec3& p : complex.vertices) {
        const double distance = samples.distance(p, 50 * voxel) / voxel;
        d.mean_voxels += distance;
        d.max_voxels = std::max(d.max_voxels, distance);
        if (distance < 0.5) ++under;
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
    // Tension and rigidity high and steps small, so that the snake bridges the holes of the thin skull (orbits,
    // foramina) rather than leaking through them.
    const surface::SnakeReport report = surface::evolve_snakes(
        complex, targets, {.tension = 0.5, .rigidity = 0.2, .max_step_voxels = 0.25, .max_iterations = 250});
    const IsoDistances d = iso_distances(complex, targets[0].field);
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

// Issue 4's done-when figures on spheres4 at 1 mm: extract -> smooth -> decimate -> remesh reduces the
// triangles at least 10x from marching cubes, keeps every vertex within half a voxel of the exact spheres
// (mean under 0.2 voxel) and every tissue's enclosed volume within 0.5% of the exact ball or shell.
#include <gtest/gtest.h>

#include <chrono>
#include <iostream>

#include "image/phantom.h"
#include "surface/check_complex.h"
#include "surface/decimate.h"
#include "surface/extract_interfaces.h"
#include "surface/extract_surface_nets.h"
#include "surface/remesh.h"
#include "surface/smooth.h"
#include "tests/support/phantom_distance.h"

namespace tissuemesh {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Prints one stage: triangles, distances to the exact spheres, volumes against the exact ones; returns the
/// largest relative volume error over the tissues.
double report_stage(const std::string& stage, const image::Phantom& phantom, const InterfaceComplex& complex,
                    double seconds)
{
    const testing::DistanceFigures figures = testing::phantom_distances(phantom, complex);
    const surface::CheckReport check = surface::check_complex(complex, {.check_intersections = false});
    std::cout << "[ figures  ] spheres4 1 mm " << stage << ": " << complex.triangle_count() << " triangles (" << seconds
              << " s); vertex distance to the exact spheres max/mean " << figures.max_voxels << "/"
              << figures.mean_voxels << " voxel; volume error";
    double worst = 0;
    for (const auto& [tissue, facts] : check.tissues) {
        if (tissue == complex.background) continue;
        const double error = facts.volume_mm3 / phantom.geometry.volume_mm3(tissue) - 1;
        std::cout << ' ' << tissue << ':' << 100 * error << '%';
        worst = std::max(worst, std::abs(error));
    }
    std::cout << "\n";
    return worst;
}

/// The chain's last two steps on `complex` (checked as `before`): decimation with `options`, remeshing to
/// 3 mm; then the issue's figures: valid, every tissue in as many pieces, at least ten times fewer triangles
/// than `cubes` (marching cubes' count), every vertex within half a voxel of the exact spheres and on average
/// within `mean_voxels`, every enclosed volume within 0.5%.
void decimate_remesh_and_check(const image::Phantom& phantom, InterfaceComplex& complex,
                               const surface::CheckReport& before, const surface::DecimateOptions& options,
                               std::size_t cubes, double mean_voxels)
{
    auto start = std::chrono::steady_clock::now();
    surface::decimate(complex, options);
    report_stage("decimated", phantom, complex, seconds_since(start));
    start = std::chrono::steady_clock::now();
    // Five rounds and relaxation moves down to 2% of the target edge, as this chain had when the figures were set:
    // the smoothed marching-cubes surface has vertices 0.53 voxel off, which five rounds of relaxation carried within
    // half a voxel; three rounds (the default since the tenth session, for the surface-nets chain) left 0.506 voxel
    // on the chain without an edge bound, and moves from 5% on (the default since the twentieth) 0.501.
    surface::remesh(complex, {.target_edge_mm = 3.0, .iterations = 5, .min_relax_move = 0.02});
    const double volume_error = report_stage("remeshed", phantom, complex, seconds_since(start));
    const testing::DistanceFigures figures = testing::phantom_distances(phantom, complex);
    const surface::CheckReport after = surface::check_complex(complex);
    EXPECT_TRUE(after.ok()) << (after.first_error() ? after.first_error()->description : "");
    for (const auto& [tissue, facts] : before.tissues)
        EXPECT_EQ(after.tissues.at(tissue).components, facts.components) << "tissue " << tissue;
    EXPECT_GE(cubes, 10 * complex.triangle_count());
    EXPECT_LE(figures.max_voxels, 0.5);
    EXPECT_LT(figures.mean_voxels, mean_voxels);
    EXPECT_LT(volume_error, 0.005);
}

/// The chain; `max_edge_mm`: the decimation's edge bound (0: none).
void run_chain(double max_edge_mm)
{
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = 1.0});
    auto start = std::chrono::steady_clock::now();
    InterfaceComplex complex = surface::extract_interfaces(phantom.image);
    const std::size_t extracted = complex.triangle_count();
    report_stage("extracted", phantom, complex, seconds_since(start));
    const surface::CheckReport before = surface::check_complex(complex);
    ASSERT_TRUE(before.ok());

    start = std::chrono::steady_clock::now();
    surface::smooth(complex, phantom.image, {.fit_passes = 3}); // Taubin alone ends 0.54 voxel off
    report_stage("smoothed", phantom, complex, seconds_since(start));
    // A quarter voxel from the smoothed surface: that surface is within 0.34 voxel of the exact spheres, and
    // the remeshed vertices land on the decimated one (with 0.5 mm the chain ended 0.54 voxel off).
    decimate_remesh_and_check(phantom, complex, before, {.max_distance_mm = 0.1, .max_edge_mm = max_edge_mm}, extracted,
                              0.2);
}

TEST(SurfaceChain, LongSpheres4At1mmMeetsTheIssueFigures) { run_chain(0); }

/// As bench/surface_chain runs it: decimation leaves no edge longer than the remeshing keeps (4/3 of 3 mm).
TEST(SurfaceChain, LongSpheres4At1mmWithTheEdgeBoundMeetsThemToo) { run_chain(4.0); }

/// Issue 27's chain, as the workflow runs it: surface nets (smoothed in their cubes), decimation at the
/// workflow's half-millimetre bound with edges below 4/3 of the target, remeshing to 3 mm.
TEST(SurfaceChain, LongSpheres4At1mmBySurfaceNetsMeetsTheIssueFigures)
{
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = 1.0});
    const std::size_t cubes = surface::extract_interfaces(phantom.image).triangle_count();
    auto start = std::chrono::steady_clock::now();
    InterfaceComplex complex = surface::extract_surface_nets(phantom.image);
    report_stage("surface nets", phantom, complex, seconds_since(start));
    const surface::CheckReport before = surface::check_complex(complex);
    ASSERT_TRUE(before.ok()) << (before.first_error() ? before.first_error()->description : "");
    decimate_remesh_and_check(phantom, complex, before, {.max_distance_mm = 0.5, .max_edge_mm = 4.0}, cubes, 0.1);
}

} // namespace
} // namespace tissuemesh

// Multi-label surface nets (extract_surface_nets): the same invariants and the same topology as the
// marching-cubes extraction, on random images with and without a priority, before and after smoothing.
#include <gtest/gtest.h>

#include <random>

#include "core/error.h"
#include "image/phantom.h"
#include "surface/check_complex.h"
#include "surface/extract_interfaces.h"
#include "surface/extract_surface_nets.h"
#include "surface/thin_first_priority.h"
#include "surface/detail/extraction_labels.h"
#include "surface/detail/net_smoother.h"
#include "surface/detail/surface_net.h"
#include "tests/surface/complex_checks.h"

namespace tissuemesh {
namespace {

using surface::extract_surface_nets;
using testing::random_image;

std::string first_error(const surface::CheckReport& report)
{
    return report.first_error() ? report.first_error()->description : "";
}

TEST(SurfaceNets, RandomImagesKeepEveryInvariantOfTheFourteenNeighbourhood)
{
    std::mt19937 random(20261204);
    for (int trial = 0; trial < 150; ++trial) {
        const LabelImage image = random_image({4, 4, 4}, random, 3);
        const InterfaceComplex complex = extract_surface_nets(image, {}, {.iterations = 0});
        ASSERT_EQ(testing::invariant_failures(image, complex, 0, true), "") << "trial " << trial;
        const surface::CheckReport report = surface::check_complex(complex);
        ASSERT_TRUE(report.ok()) << "trial " << trial << ": " << first_error(report);
    }
}

TEST(SurfaceNets, RandomImagesWithRandomPrioritiesKeepEveryInvariant)
{
    std::mt19937 random(41);
    std::uniform_int_distribution<int> value(-2, 3), coin(0, 1);
    for (int trial = 0; trial < 150; ++trial) {
        const LabelImage image = random_image({4, 4, 4}, random, 3);
        std::map<Label, int> priority;
        for (Label label = 0; label <= 3; ++label)
            if (coin(random) && count_labels(image).contains(label)) priority[label] = value(random);
        if (priority.empty()) priority[image.at(0, 0, 0)] = 1;
        const InterfaceComplex complex = extract_surface_nets(image, {.priority = priority}, {.iterations = 0});
        ASSERT_EQ(testing::invariant_failures(image, complex, 0, true, priority), "") << "trial " << trial;
        const surface::CheckReport report = surface::check_complex(complex);
        ASSERT_TRUE(report.ok()) << "trial " << trial << ": " << first_error(report);
    }
}

TEST(SurfaceNets, SmoothedRandomImagesStayFitAndKeepTheirTopology)
{
    std::mt19937 random(7);
    for (int trial = 0; trial < 60; ++trial) {
        const LabelImage image = random_image({6, 5, 5}, random, 2);
        const InterfaceComplex raw = extract_surface_nets(image, {}, {.iterations = 0});
        const InterfaceComplex smooth = extract_surface_nets(image);
        const surface::CheckReport before = surface::check_complex(raw), after = surface::check_complex(smooth);
        ASSERT_TRUE(after.ok()) << "trial " << trial << ": " << first_error(after);
        for (const auto& [label, facts] : before.tissues)
            EXPECT_EQ(after.tissues.at(label).components, facts.components) << "trial " << trial;
    }
}

TEST(SurfaceNets, SphereHeadAt2mmIsFitWithFewerTrianglesThanMarchingCubes)
{
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = 2.0});
    const std::map<Label, int> priority{{3, 1}};
    surface::SurfaceNetsReport report;
    const InterfaceComplex nets = extract_surface_nets(phantom.image, {.priority = priority}, {}, {}, &report);
    const InterfaceComplex cubes = surface::extract_interfaces(phantom.image, {.priority = priority});
    const surface::CheckReport check = surface::check_complex(nets);
    ASSERT_TRUE(check.ok()) << first_error(check);
    // The one-voxel CSF keeps many cubes as their tetrahedra (its faces are crossed by two sheets), so the
    // net is only a third smaller here; on the 1 mm phantom most cubes merge (next test).
    EXPECT_LT(3 * nets.triangle_count(), 2 * cubes.triangle_count());
    EXPECT_GT(report.fallback_cubes, 0u);
    // The one-voxel CSF keeps one piece (two surfaces: against skull and brain).
    EXPECT_EQ(check.tissues.at(3).components, 2u);
    EXPECT_GT(report.moves, 0u);
}

TEST(SurfaceNets, SphereHeadAt1mmHasAboutTwoTrianglesPerVoxelFace)
{
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = 1.0});
    surface::SurfaceNetsReport report;
    const InterfaceComplex nets = extract_surface_nets(phantom.image, {}, {.iterations = 0}, {}, &report);
    std::size_t faces = 0; // voxel faces between two labels (the image's outside counts as background)
    const Dims& d = phantom.image.dims();
    for (std::size_t k = 0; k < d[2]; ++k)
        for (std::size_t j = 0; j < d[1]; ++j)
            for (std::size_t i = 0; i + 1 < d[0]; ++i) {
                faces += phantom.image.at(i, j, k) != phantom.image.at(i + 1, j, k);
                if (j + 1 < d[1]) faces += phantom.image.at(i, j, k) != phantom.image.at(i, j + 1, k);
                if (k + 1 < d[2]) faces += phantom.image.at(i, j, k) != phantom.image.at(i, j, k + 1);
            }
    // Every cube merges but a few (a digital sphere has no thin layer at 1 mm): two triangles per face.
    EXPECT_LT(report.fallback_cubes * 100, report.mixed_cubes);
    EXPECT_GE(nets.triangle_count(), 2 * faces);
    EXPECT_LT(nets.triangle_count(), 2 * faces + 2 * faces / 20);
}

/// The invariant the smoothing's local checks rest on: every vertex stays inside its cube (shrunk by the
/// margin). After smoothing none is outside; a vertex pushed out of its cube is caught by the guard that
/// smooth_net() runs at its end (it would otherwise meet triangles the fixed list of pairs does not watch).
TEST(SurfaceNets, AVertexPushedOutOfItsCubeIsCaught)
{
    const image::Phantom phantom = image::make_phantom("junction", {.voxel_mm = 3.0});
    const surface::detail::ExtractionLabels labels =
        surface::detail::prepare_extraction(phantom.image, {}, 0, {}, 0, "test");
    surface::detail::SurfaceNet net = surface::detail::build_surface_net(phantom.image, labels.map, 0, {});
    const surface::NetSmoothOptions options;
    surface::SurfaceNetsReport report;
    surface::detail::smooth_net(net, phantom.image, labels.map, 0, options, {}, report);
    ASSERT_GT(report.moves, 0u);
    EXPECT_EQ(surface::detail::vertices_outside_boxes(net, options.margin_voxels), 0u);
    std::size_t pushed = 0;
    for (std::size_t v = 0; v < net.positions.size() && pushed == 0; ++v)
        if (net.kinds[v] == surface::detail::NetVertexKind::cube) {
            net.positions[v][0] = net.boxes[v].high[0] + 0.3; // into the neighbouring cube
            pushed = 1;
        }
    ASSERT_EQ(pushed, 1u);
    EXPECT_EQ(surface::detail::vertices_outside_boxes(net, options.margin_voxels), 1u);
    // Within the box but closer to its face than the margin: also outside what the checks assume.
    for (std::size_t v = 0; v < net.positions.size(); ++v)
        if (net.kinds[v] == surface::detail::NetVertexKind::cube) {
            net.positions[v][0] = net.boxes[v].high[0] - 0.5 * options.margin_voxels;
            break;
        }
    EXPECT_EQ(surface::detail::vertices_outside_boxes(net, options.margin_voxels), 1u);
}

TEST(SurfaceNets, RejectsBadSmoothingOptions)
{
    const image::Phantom phantom = image::make_phantom("junction", {.voxel_mm = 4.0});
    EXPECT_THROW(extract_surface_nets(phantom.image, {}, {.lambda = 0}), InputError);
    EXPECT_THROW(extract_surface_nets(phantom.image, {}, {.mu = -0.5}), InputError);
    EXPECT_THROW(extract_surface_nets(phantom.image, {}, {.margin_voxels = 0.5}), InputError);
    EXPECT_THROW(extract_surface_nets(phantom.image, {}, {.max_depth_voxels = 0}), InputError);
    EXPECT_THROW(extract_surface_nets(phantom.image, {}, {.pairs_per_check = 0}), InputError);
    EXPECT_THROW(extract_surface_nets(phantom.image, {.tissues = {9}}), InputError);
}

/// The automatic priority ranks the thinnest tissue first: the sphere head's CSF (a 6 mm shell at 2 mm:
/// three voxels), the thin phantom's one-voxel shell; with it the 2 mm sphere head's CSF is one piece.
TEST(ThinFirstPriority, RanksThinLayersFirstAndKeepsThemWhole)
{
    const image::Phantom head = image::make_phantom("spheres4", {.voxel_mm = 2.0});
    const std::map<Label, int> priority = surface::thin_first_priority(head.image);
    ASSERT_EQ(priority.size(), 4u); // scalp, skull, CSF, brain; not the background
    for (const auto& [label, rank] : priority)
        if (label != 3) {
            EXPECT_GT(priority.at(3), rank) << "CSF against " << label;
        }
    EXPECT_GT(priority.at(2), priority.at(4)); // the skull shell is thinner than the brain ball
    const InterfaceComplex complex = extract_surface_nets(head.image, {.priority = priority});
    const surface::CheckReport check = surface::check_complex(complex);
    ASSERT_TRUE(check.ok()) << first_error(check);
    EXPECT_EQ(check.tissues.at(3).components, 2u);

    const image::Phantom thin = image::make_phantom("thin", {.voxel_mm = 1.0});
    const std::map<Label, int> shell_first = surface::thin_first_priority(thin.image);
    EXPECT_GT(shell_first.at(1), shell_first.at(2));
    EXPECT_THROW(surface::thin_first_priority(LabelImage{}), InputError);
}

} // namespace
} // namespace tissuemesh

// remesh() in slabs: each slab remeshed on its own behind a fence, then bands around the cuts. The result
// must be as valid as remeshing the whole at once, as close to the input, and about as regular.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "core/error.h"
#include "image/phantom.h"
#include "surface/check_complex.h"
#include "surface/decimate.h"
#include "surface/extract_interfaces.h"
#include "surface/remesh.h"
#include "surface/smooth.h"
#include "tests/support/phantom_distance.h"
#include "tests/support/slab_comparison.h"

namespace tissuemesh {
namespace {

struct Outcome {
    InterfaceComplex complex;
    surface::RemeshReport report;
    surface::CheckReport check;
    testing::DistanceFigures distances;
};

Outcome remesh_in(const image::Phantom& phantom, const InterfaceComplex& input, double edge_mm, std::size_t slabs)
{
    Outcome outcome{input, {}, {}, {}};
    outcome.report = surface::remesh(outcome.complex, {.target_edge_mm = edge_mm, .slabs = slabs});
    outcome.check = surface::check_complex(outcome.complex);
    outcome.distances = testing::phantom_distances(phantom, outcome.complex);
    return outcome;
}

void compare_slabs_with_whole(const std::string& name, double voxel_mm, double edge_mm, std::size_t slabs)
{
    const image::Phantom phantom = image::make_phantom(name, {.voxel_mm = voxel_mm});
    InterfaceComplex input = surface::extract_interfaces(phantom.image);
    surface::smooth(input, phantom.image);
    surface::decimate(input, {.max_distance_mm = 0.5});
    const surface::CheckReport before = surface::check_complex(input);
    ASSERT_TRUE(before.ok());
    const Outcome whole = remesh_in(phantom, input, edge_mm, 1);
    const Outcome cut = remesh_in(phantom, input, edge_mm, slabs);
    const auto line = [](const Outcome& o) {
        return concat(o.report.triangles_after, " triangles, mean edge ", format_mm(o.report.mean_edge_after_mm, 3),
                      " mm, smallest angle ", format_mm(o.report.min_angle_after_deg, 2), " deg, to the input max ",
                      format_mm(o.report.max_distance_mm, 3), " mm, to the exact interfaces max/mean ",
                      format_mm(o.distances.max_voxels, 3), "/", format_mm(o.distances.mean_voxels, 3), " voxel");
    };
    std::cout << "[ figures  ] " << name << " at " << voxel_mm << " mm, " << input.triangle_count() << " triangles, "
              << edge_mm << " mm edges: whole -> " << line(whole) << "; " << cut.report.slabs << " slabs -> "
              << line(cut) << "\n";
    EXPECT_EQ(whole.report.slabs, 1u);
    // Fewer when a slab would be narrower than ten target edges.
    EXPECT_GE(cut.report.slabs, 2u);
    EXPECT_LE(cut.report.slabs, slabs);
    testing::expect_slabs_keep_the_whole(cut.check, whole.check, before);
    // The edits differ in their order near the cuts and the seam bands get a second round: counts and sizes
    // agree within a few percent (figures above).
    EXPECT_NEAR(static_cast<double>(cut.report.triangles_after), static_cast<double>(whole.report.triangles_after),
                0.05 * static_cast<double>(whole.report.triangles_after));
    EXPECT_NEAR(cut.report.mean_edge_after_mm, whole.report.mean_edge_after_mm, 0.03 * whole.report.mean_edge_after_mm);
    EXPECT_GE(cut.report.min_angle_after_deg, std::min(whole.report.min_angle_after_deg, 5.0) - 1e-9);
    EXPECT_LE(cut.report.max_distance_mm, whole.report.max_distance_mm + 0.1);
    EXPECT_LE(cut.distances.mean_voxels, whole.distances.mean_voxels + 0.01);
}

TEST(RemeshSlabs, ThinShellInFourSlabsMatchesTheWhole) { compare_slabs_with_whole("thin", 1.0, 1.5, 4); }

TEST(RemeshSlabs, JunctionInFiveSlabsMatchesTheWhole) { compare_slabs_with_whole("junction", 1.0, 2.0, 5); }

} // namespace
} // namespace tissuemesh

// Every phantom, and the liver, torso and head samples: the extracted complex (marching cubes, and surface
// nets smoothed) is fit for tetrahedralization, no tissue is lost, and each tissue's surface pieces follow its
// voxel pieces under the 14-neighbourhood rule (or the priority rule).
#include <gtest/gtest.h>

#include "core/error.h"
#include "image/phantom.h"
#include "io/read_label_image.h"
#include "surface/check_complex.h"
#include "surface/extract_interfaces.h"
#include "surface/extract_surface_nets.h"
#include "tests/support/cli.h"
#include "tests/surface/complex_checks.h"

namespace tissuemesh {
namespace {

enum class Method { marching_cubes, surface_nets };

InterfaceComplex extract(const LabelImage& image, const surface::ExtractOptions& options, Method method)
{
    return method == Method::surface_nets ? surface::extract_surface_nets(image, options)
                                          : surface::extract_interfaces(image, options);
}

/// Checks the complex of `image` and returns nothing; failures are reported with `what`.
void expect_fit_and_complete(const LabelImage& image, const std::string& what, Method method = Method::marching_cubes)
{
    const InterfaceComplex complex = extract(image, {}, method);
    const surface::CheckReport report = surface::check_complex(complex);
    EXPECT_TRUE(report.ok()) << what << ": " << (report.first_error() ? report.first_error()->description : "");
    for (const auto& [label, voxels] : count_labels(image)) {
        ASSERT_TRUE(report.tissues.contains(label)) << what << ": tissue " << label << " lost";
        if (label == complex.background) continue;
        // A region with P pieces whose complement has Q pieces is bounded by P + Q - 1 closed surfaces
        // (each piece of the rest touching the region adds one boundary; the outside is shared).
        const std::size_t pieces = testing::voxel_components(image, label, complex.background, false);
        const std::size_t rest = testing::voxel_components(image, label, complex.background, true);
        EXPECT_EQ(report.tissues.at(label).components, pieces + rest - 1) << what << ": tissue " << label;
        EXPECT_TRUE(report.tissues.at(label).closed) << what << ": tissue " << label;
    }
}

class ExtractPhantom : public ::testing::TestWithParam<const char*> {};

TEST_P(ExtractPhantom, FitForTetrahedralizationAt2mm)
{
    const image::Phantom phantom = image::make_phantom(GetParam(), {.voxel_mm = 2.0});
    expect_fit_and_complete(phantom.image, GetParam());
}

INSTANTIATE_TEST_SUITE_P(AllPhantoms, ExtractPhantom,
                         ::testing::Values("spheres4", "junction", "thin", "boxes", "ellipsoids"));

/// The complex of `image` under `priority` is fit, complete, and its pieces follow the priority rule.
void expect_fit_under_priority(const LabelImage& image, const std::map<Label, int>& priority, const std::string& what,
                               Method method = Method::marching_cubes)
{
    const InterfaceComplex complex = extract(image, {.priority = priority}, method);
    const surface::CheckReport report = surface::check_complex(complex);
    EXPECT_TRUE(report.ok()) << what << ": " << (report.first_error() ? report.first_error()->description : "");
    for (const auto& [label, voxels] : count_labels(image)) {
        ASSERT_TRUE(report.tissues.contains(label)) << what << ": tissue " << label << " lost";
        if (label == complex.background) continue;
        // P pieces and Q pieces of the rest give P + Q - 1 closed surfaces, counted under the rule.
        const std::size_t pieces = testing::priority_components(image, label, complex.background, false, priority);
        const std::size_t rest = testing::priority_components(image, label, complex.background, true, priority);
        EXPECT_EQ(report.tissues.at(label).components, pieces + rest - 1) << what << ": tissue " << label;
        EXPECT_TRUE(report.tissues.at(label).closed) << what << ": tissue " << label;
    }
}

TEST_P(ExtractPhantom, LongFitUnderEachSingleTissuePriorityAt2mm)
{
    const image::Phantom phantom = image::make_phantom(GetParam(), {.voxel_mm = 2.0});
    for (const auto& [label, voxels] : count_labels(phantom.image))
        if (label != 0) expect_fit_under_priority(phantom.image, {{label, 1}}, concat(GetParam(), " priority ", label));
}

TEST_P(ExtractPhantom, FitUnderRankedPrioritiesAt2mm)
{
    // Every tissue listed, the larger label higher: ties never arise, every cube has a listed top label.
    const image::Phantom phantom = image::make_phantom(GetParam(), {.voxel_mm = 2.0});
    std::map<Label, int> priority;
    for (const auto& [label, voxels] : count_labels(phantom.image)) priority[label] = label;
    expect_fit_under_priority(phantom.image, priority, concat(GetParam(), " ranked"));
}

/// The thin phantom's one-voxel shell (tissue 1) with a priority for it, at 1 and 2 mm: valid, the shell one
/// piece between two closed surfaces, the ball inside one piece. Surface nets also give the shell a positive
/// thickness everywhere: its two surfaces share no vertex (its cubes never merge the inside and outside
/// sheets) and enclose a positive volume.
void expect_thin_shell_in_one_piece(Method method)
{
    const std::map<Label, int> priority{{1, 1}};
    for (const double voxel_mm : {1.0, 2.0}) {
        const image::Phantom phantom = image::make_phantom("thin", {.voxel_mm = voxel_mm});
        const InterfaceComplex complex = extract(phantom.image, {.priority = priority}, method);
        const surface::CheckReport report = surface::check_complex(complex);
        ASSERT_TRUE(report.ok()) << voxel_mm << " mm";
        if (method == Method::marching_cubes) {
            EXPECT_EQ(testing::priority_components(phantom.image, 1, 0, false, priority), 1u) << voxel_mm << " mm";
        }
        EXPECT_EQ(report.tissues.at(1).components, 2u) << voxel_mm << " mm";
        EXPECT_EQ(report.tissues.at(2).components, 1u) << voxel_mm << " mm";
        if (method == Method::surface_nets) {
            EXPECT_GT(report.tissues.at(1).volume_mm3, 0) << voxel_mm << " mm";
        }
    }
}

// Under the plain 14-neighbourhood a one-voxel shell breaks into pieces where it touches itself only
// diagonally (7 pieces at 1 mm) and the ball inside leaks through the gaps at 2 mm; a priority for the
// shell keeps it one piece between two closed surfaces.
TEST(ExtractPhantomThin, OneVoxelShellStaysOneClosedPieceWithPriority)
{
    expect_thin_shell_in_one_piece(Method::marching_cubes);
}

TEST(ExtractSample, LongLiverIsFitForTetrahedralization)
{
    const LabelImage image = io::read_label_image(testing::data_path("samples/liver.inr.gz"));
    expect_fit_and_complete(image, "liver.inr.gz");
}

class NetsPhantom : public ::testing::TestWithParam<const char*> {};

TEST_P(NetsPhantom, FitForTetrahedralizationAt2mm)
{
    const image::Phantom phantom = image::make_phantom(GetParam(), {.voxel_mm = 2.0});
    expect_fit_and_complete(phantom.image, GetParam(), Method::surface_nets);
}

TEST_P(NetsPhantom, FitUnderRankedPrioritiesAt2mm)
{
    const image::Phantom phantom = image::make_phantom(GetParam(), {.voxel_mm = 2.0});
    std::map<Label, int> priority;
    for (const auto& [label, voxels] : count_labels(phantom.image)) priority[label] = label;
    expect_fit_under_priority(phantom.image, priority, concat(GetParam(), " ranked"), Method::surface_nets);
}

INSTANTIATE_TEST_SUITE_P(AllPhantoms, NetsPhantom,
                         ::testing::Values("spheres4", "junction", "thin", "boxes", "ellipsoids"));

TEST(NetsPhantomThin, OneVoxelShellStaysOneClosedPieceWithPriority)
{
    expect_thin_shell_in_one_piece(Method::surface_nets);
}

TEST(NetsSample, LongLiverTorsoAndHeadAreFitForTetrahedralization)
{
    for (const char* sample :
         {"samples/liver.inr.gz", "samples/totalseg_torso_3mm.nii.gz", "samples/usc19-5_head.nii.gz"}) {
        const LabelImage image = io::read_label_image(testing::data_path(sample));
        expect_fit_and_complete(image, sample, Method::surface_nets);
    }
    const LabelImage head = io::read_label_image(testing::data_path("samples/usc19-5_head.nii.gz"));
    expect_fit_under_priority(head, {{3, 1}}, "usc19-5 with the CSF first", Method::surface_nets);
}

} // namespace
} // namespace tissuemesh

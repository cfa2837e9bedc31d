#include <gtest/gtest.h>

#include "core/error.h"
#include "image/crop_to_tissue.h"
#include "image/fill_holes.h"
#include "image/keep_largest_component.h"
#include "image/phantom.h"
#include "image/prepare_image.h"
#include "image/relabel.h"
#include "image/remove_islands.h"
#include "image/resample_labels.h"
#include "tests/support/error_message.h"

namespace tissuemesh::image {
namespace {

/// Sets the voxels of the index box [lo, hi] (inclusive) to `label`.
void fill_box(LabelImage& image, std::array<std::size_t, 3> lo, std::array<std::size_t, 3> hi, Label label)
{
    for (std::size_t k = lo[2]; k <= hi[2]; ++k)
        for (std::size_t j = lo[1]; j <= hi[1]; ++j)
            for (std::size_t i = lo[0]; i <= hi[0]; ++i) image.at(i, j, k) = label;
}

TEST(Relabel, SwapsAtOnceAndCarriesNames)
{
    LabelImage image({4, 4, 4}, {1, 1, 1});
    fill_box(image, {0, 0, 0}, {1, 3, 3}, 1); // 32 voxels
    fill_box(image, {2, 0, 0}, {2, 3, 3}, 2); // 16 voxels
    image.names() = {{1, "scalp"}, {2, "skull"}};
    const PrepReport report = relabel(image, {{1, 2}, {2, 1}});
    EXPECT_EQ(count_labels(image).at(2), 32u);
    EXPECT_EQ(count_labels(image).at(1), 16u);
    EXPECT_EQ(report.changed_voxels, 48u);
    EXPECT_EQ(report.voxels_before.at(1), 32u);
    EXPECT_EQ(report.voxels_after.at(1), 16u);
    EXPECT_EQ(image.names().at(2), "scalp");
    EXPECT_EQ(testing::input_error_message([&] {
                  relabel(image, {{7, 0}});
              }),
              "relabel 7:0: label 7 is not in the image (it has 0,1,2); check the map against tm-info");
}

TEST(Relabel, MergesIntoTheFirstLabel)
{
    LabelImage image({3, 1, 1}, {1, 1, 1});
    image.at(0, 0, 0) = 4, image.at(1, 0, 0) = 5, image.at(2, 0, 0) = 6;
    const PrepReport report = merge_labels(image, {4, 5, 6});
    EXPECT_EQ(count_labels(image), (std::map<Label, std::size_t>{{4, 3}}));
    EXPECT_EQ(report.changed_voxels, 2u);
    EXPECT_THROW(merge_labels(image, {4}), InputError);
    EXPECT_THROW(merge_labels(image, {9, 4}), InputError);
}

TEST(CropToTissue, CropsToTheTissueBoxAndPadsWithoutMovingVoxels)
{
    const Mat3 flip{-1, 0, 0, 0, 1, 0, 0, 0, -1}; // a rotation: the origin must follow the direction
    LabelImage image({10, 10, 10}, {1, 2, 3}, {5, 6, 7}, flip);
    fill_box(image, {3, 4, 2}, {5, 4, 6}, 1);
    image.at(4, 4, 4) = 2;
    const Vec3 tissue_world = image.index_to_world({4, 4, 4});
    const PrepReport report = crop_to_tissue(image, {.pad_voxels = 2});
    EXPECT_EQ(image.dims(), (Dims{7, 5, 9}));
    EXPECT_EQ(image.at(3, 2, 4), 2); // old (4,4,4) minus the new start (1,2,0)
    const Vec3 moved = image.index_to_world({3, 2, 4});
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(moved[a], tissue_world[a], 1e-12);
    EXPECT_EQ(report.voxels_after.at(1), report.voxels_before.at(1));
    EXPECT_EQ(report.voxels_after.at(2), 1u);
}

TEST(CropToTissue, PadsBeyondTheOldBorder)
{
    LabelImage image({3, 3, 3}, {1, 1, 1});
    image.at(0, 1, 2) = 1; // on the border
    crop_to_tissue(image, {.pad_voxels = 3});
    EXPECT_EQ(image.dims(), (Dims{7, 7, 7}));
    EXPECT_EQ(image.at(3, 3, 3), 1);
    EXPECT_EQ(count_labels(image).at(0), 342u);
    LabelImage empty({2, 2, 2}, {1, 1, 1});
    EXPECT_THROW(crop_to_tissue(empty), InputError);
}

TEST(Resample, DownsamplesByMajorityOfTheOverlap)
{
    LabelImage image({4, 4, 4}, {1, 1, 1});
    fill_box(image, {0, 0, 0}, {1, 1, 1}, 1); // fills new voxel (0,0,0) entirely
    fill_box(image, {2, 2, 2}, {3, 3, 2}, 2); // half of new voxel (1,1,1): a tie with background
    image.at(3, 0, 0) = 3;                    // 1/8 of new voxel (1,0,0): loses to background
    const PrepReport report = resample_labels(image, {.spacing_mm = {2, 2, 2}});
    EXPECT_EQ(image.dims(), (Dims{2, 2, 2}));
    EXPECT_EQ(report.dims_before, (Dims{4, 4, 4}));
    EXPECT_NE(report.detail.find("4x4x4 -> 2x2x2 voxels"), std::string::npos) << report.detail;
    EXPECT_EQ(image.at(0, 0, 0), 1);
    EXPECT_EQ(image.at(1, 1, 1), 2); // ties go to the tissue
    EXPECT_EQ(image.at(1, 0, 0), 0);
    // The new first voxel is centred on the old voxels 0 and 1: old continuous index 0.5.
    EXPECT_DOUBLE_EQ(image.origin_mm()[0], 0.5);
}

TEST(Resample, UpsamplesExactlyAndHandlesAnisotropy)
{
    LabelImage image({4, 4, 6}, {1, 1, 1});
    fill_box(image, {1, 1, 0}, {2, 2, 5}, 1); // 24 voxels of 1 mm^3
    LabelImage fine = image;
    resample_labels(fine, {.spacing_mm = {0.5, 0.5, 0.5}});
    EXPECT_EQ(fine.dims(), (Dims{8, 8, 12}));
    EXPECT_EQ(count_labels(fine).at(1), 24u * 8u); // every new cell lies inside one old voxel
    LabelImage coarse_z = image;
    resample_labels(coarse_z, {.spacing_mm = {1, 1, 3}, .method = ResampleMethod::nearest});
    EXPECT_EQ(coarse_z.dims(), (Dims{4, 4, 2}));
    EXPECT_EQ(count_labels(coarse_z).at(1), 8u);
    EXPECT_THROW(resample_labels(image, {.spacing_mm = {1, 0, 1}}), InputError);
    EXPECT_THROW(resample_labels(image, {.spacing_mm = {1, 1, NAN}}), InputError);
}

TEST(Resample, KeepsPhantomVolumes)
{
    // Majority resampling from 1 mm to 2.5 mm keeps each thick tissue's volume within 3%: the class of a
    // boundary cell follows its larger share, so errors cancel along smooth surfaces.
    Phantom phantom = make_phantom("ellipsoids", {.voxel_mm = 1.0});
    resample_labels(phantom.image, {.spacing_mm = {2.5, 2.5, 2.5}});
    const auto counts = count_labels(phantom.image);
    for (const Label label : phantom.geometry.tissues())
        EXPECT_NEAR(static_cast<double>(counts.at(label)) * phantom.image.voxel_volume_mm3() /
                        phantom.geometry.volume_mm3(label),
                    1.0, 0.03)
            << label;
}

TEST(RemoveIslands, GivesSmallPiecesToTheirSurroundings)
{
    LabelImage image({10, 10, 10}, {1, 1, 1});
    fill_box(image, {0, 0, 0}, {4, 9, 9}, 1);     // a big slab of 1
    image.at(2, 5, 5) = 2;                        // a 1-voxel island of 2 inside the slab
    image.at(8, 5, 5) = 3, image.at(8, 5, 6) = 3; // a 2-voxel island of 3 in the background
    fill_box(image, {7, 0, 0}, {8, 2, 2}, 4);     // 18 voxels of 4: large enough to stay
    const PrepReport report = remove_islands(image, {.min_voxels = 5});
    EXPECT_EQ(image.at(2, 5, 5), 1);
    EXPECT_EQ(image.at(8, 5, 5), 0);
    EXPECT_EQ(image.at(8, 5, 6), 0);
    EXPECT_EQ(count_labels(image).at(4), 18u);
    EXPECT_EQ(report.changed_voxels, 3u);
    EXPECT_FALSE(count_labels(image).contains(2));
}

TEST(RemoveIslands, IslandsSurroundedByIslandsGoToWhatStays)
{
    // A voxel of 3 wrapped by six single voxels of 2 (not face-connected to each other), in background.
    // The 2s join the background around them; the 3, touching only islands, first takes their label
    // and, now a lone island of 2, joins the background in the next round.
    LabelImage image({7, 7, 7}, {1, 1, 1});
    image.at(3, 3, 3) = 3;
    for (int a = 0; a < 3; ++a)
        for (const int step : {-1, 1}) {
            std::array<std::size_t, 3> index{3, 3, 3};
            index[a] = static_cast<std::size_t>(3 + step);
            image.at(index[0], index[1], index[2]) = 2;
        }
    const PrepReport report = remove_islands(image, {.min_voxels = 5, .connectivity = Connectivity::faces6});
    EXPECT_EQ(count_labels(image), (std::map<Label, std::size_t>{{0, 343}}));
    EXPECT_EQ(report.changed_voxels, 7u);
}

TEST(FillHoles, FillsEnclosedBackgroundOnly)
{
    LabelImage image({9, 9, 9}, {1, 1, 1});
    fill_box(image, {1, 1, 1}, {7, 7, 7}, 1);
    fill_box(image, {3, 3, 3}, {4, 4, 4}, 0); // an 8-voxel cavity
    image.at(7, 4, 4) = 0;                    // a dent open to the outside: not a hole
    const PrepReport report = fill_holes(image);
    EXPECT_EQ(image.at(3, 3, 3), 1);
    EXPECT_EQ(image.at(7, 4, 4), 0);
    EXPECT_EQ(report.changed_voxels, 8u);
}

TEST(FillHoles, RestrictsToHolesInChosenTissues)
{
    LabelImage image({9, 9, 9}, {1, 1, 1});
    fill_box(image, {1, 1, 1}, {7, 7, 7}, 1);
    fill_box(image, {2, 2, 2}, {4, 4, 4}, 2);
    image.at(3, 3, 3) = 0; // a cavity inside tissue 2 only
    image.at(6, 6, 6) = 0; // a cavity inside tissue 1 only
    FillHolesOptions options{.tissues = {1}};
    fill_holes(image, options);
    EXPECT_EQ(image.at(3, 3, 3), 0);
    EXPECT_EQ(image.at(6, 6, 6), 1);
    fill_holes(image);
    EXPECT_EQ(image.at(3, 3, 3), 2);
}

TEST(FillHoles, FillsOnlySpecksUnderTheGivenSize)
{
    LabelImage image({12, 9, 9}, {1, 1, 1});
    fill_box(image, {1, 1, 1}, {10, 7, 7}, 1);
    fill_box(image, {2, 3, 3}, {3, 4, 4}, 0); // an 8-voxel cavity
    image.at(7, 4, 4) = 0;                    // a one-voxel speck
    const PrepReport report = fill_holes(image, {.under_voxels = 8});
    EXPECT_EQ(image.at(7, 4, 4), 1);
    EXPECT_EQ(image.at(2, 3, 3), 0);
    EXPECT_EQ(report.changed_voxels, 1u);
    EXPECT_NE(report.detail.find("under 8 voxels"), std::string::npos) << report.detail;
}

TEST(KeepLargestComponent, DropsSmallerPieces)
{
    LabelImage image({8, 8, 8}, {1, 1, 1});
    fill_box(image, {1, 1, 1}, {3, 3, 3}, 1); // 27 voxels: kept
    fill_box(image, {5, 5, 5}, {6, 6, 5}, 1); // 4 voxels in the background: dropped
    fill_box(image, {5, 1, 1}, {6, 2, 2}, 2); // another label, untouched
    image.at(6, 1, 3) = 2;                    // a second piece of 2, but 2 is not chosen
    const PrepReport report = keep_largest_component(image, {1});
    EXPECT_EQ(count_labels(image).at(1), 27u);
    EXPECT_EQ(count_labels(image).at(2), 9u);
    EXPECT_EQ(report.changed_voxels, 4u);
    EXPECT_THROW(keep_largest_component(image, {7}), InputError);
}

TEST(PrepareImage, AppliesStepsInTheDocumentedOrder)
{
    LabelImage image({12, 12, 12}, {1, 1, 1});
    fill_box(image, {3, 3, 3}, {8, 8, 8}, 5);
    image.at(5, 5, 5) = 6; // an island that the relabel turns into 5 before islands are looked at
    image.at(0, 0, 0) = 7; // a stray voxel at the corner: removed as an island before the crop
    PrepOptions options;
    options.relabel = {{5, 1}, {6, 1}};
    options.remove_islands_voxels = 2;
    options.crop_pad_voxels = 1;
    const auto reports = prepare_image(image, options);
    ASSERT_EQ(reports.size(), 3u);
    EXPECT_EQ(reports[0].step, "relabel");
    EXPECT_EQ(reports[1].step, "remove-islands");
    EXPECT_EQ(reports[1].changed_voxels, 1u); // only the corner voxel
    EXPECT_EQ(reports[2].step, "crop-pad");
    EXPECT_EQ(image.dims(), (Dims{8, 8, 8}));
    EXPECT_EQ(count_labels(image), (std::map<Label, std::size_t>{{0, 512 - 216}, {1, 216}}));

    LabelImage untouched = image;
    PrepOptions bad;
    bad.relabel = {{1, 2}};
    bad.spacing_mm = Vec3{1, 0, 1};
    EXPECT_THROW(prepare_image(untouched, bad), InputError);
    EXPECT_EQ(untouched.labels(), image.labels()); // options are checked before any step runs
}

} // namespace
} // namespace tissuemesh::image

#include <gtest/gtest.h>

#include "core/error.h"
#include "image/connected_components.h"
#include "image/label_statistics.h"
#include "image/phantom.h"
#include "io/read_label_image.h"
#include "tests/support/cli.h"

#include <fstream>
#include <nlohmann/json.hpp>

namespace tissuemesh::image {
namespace {

const LabelSummary& summary_of(const LabelStatistics& stats, Label label)
{
    for (const auto& s : stats.labels)
        if (s.label == label) return s;
    throw std::runtime_error("label missing");
}

/// A 6 x 6 x 6 background image with the given voxels set.
LabelImage tiny(std::initializer_list<std::pair<Index3, Label>> voxels)
{
    LabelImage image({6, 6, 6}, {1, 1, 2});
    for (const auto& [index, label] : voxels)
        image.at(static_cast<std::size_t>(index[0]), static_cast<std::size_t>(index[1]),
                 static_cast<std::size_t>(index[2])) = label;
    return image;
}

TEST(LabelStatistics, DiagonalPairIsOneComponentOnlyWith26Neighbours)
{
    const LabelImage image = tiny({{{2, 2, 2}, 1}, {{3, 3, 3}, 1}});
    const LabelStatistics stats = analyze_labels(image);
    const LabelSummary& s = summary_of(stats, 1);
    EXPECT_EQ(s.voxels, 2u);
    EXPECT_EQ(s.components6, 2u);
    EXPECT_EQ(s.components26, 1u);
    EXPECT_DOUBLE_EQ(s.volume_mm3, 4.0); // two voxels of 1 x 1 x 2 mm
    EXPECT_EQ(s.index_min, (std::array<std::size_t, 3>{2, 2, 2}));
    EXPECT_EQ(s.index_max, (std::array<std::size_t, 3>{3, 3, 3}));
    // The cells span index 1.5 .. 3.5: along z (2 mm voxels) that is 3 .. 7 mm.
    EXPECT_DOUBLE_EQ(s.bounds_mm[0][2], 3.0);
    EXPECT_DOUBLE_EQ(s.bounds_mm[1][2], 7.0);
    EXPECT_DOUBLE_EQ(s.bounds_mm[0][0], 1.5);
    // Edge neighbours (a diagonal in one plane) also join under 26 only.
    const LabelStatistics edge = analyze_labels(tiny({{{2, 2, 2}, 1}, {{3, 3, 2}, 1}}));
    EXPECT_EQ(summary_of(edge, 1).components6, 2u);
    EXPECT_EQ(summary_of(edge, 1).components26, 1u);
}

TEST(LabelStatistics, ReportsTouchingLabelsThroughFacesOnly)
{
    // 1 and 2 share a face; 3 touches 2 only at a corner, so not through a face.
    const LabelImage image = tiny({{{2, 2, 2}, 1}, {{3, 2, 2}, 2}, {{4, 3, 3}, 3}});
    const LabelStatistics stats = analyze_labels(image);
    EXPECT_EQ(summary_of(stats, 1).touches, (std::vector<Label>{0, 2}));
    EXPECT_EQ(summary_of(stats, 2).touches, (std::vector<Label>{0, 1}));
    EXPECT_EQ(summary_of(stats, 3).touches, (std::vector<Label>{0}));
    EXPECT_EQ(summary_of(stats, 0).touches, (std::vector<Label>{1, 2, 3}));
}

TEST(LabelStatistics, WarnsAboutTissueOnTheBorder)
{
    const LabelStatistics stats = analyze_labels(tiny({{{0, 3, 3}, 1}, {{5, 5, 5}, 1}, {{2, 2, 2}, 2}}));
    EXPECT_EQ(summary_of(stats, 1).border_voxels, 2u);
    EXPECT_EQ(summary_of(stats, 2).border_voxels, 0u);
    ASSERT_FALSE(summary_of(stats, 1).warnings.empty());
    EXPECT_NE(summary_of(stats, 1).warnings[0].find("2 voxels on the image border"), std::string::npos);
    EXPECT_NE(summary_of(stats, 1).warnings[0].find("tm-prep --crop-pad"), std::string::npos);
    EXPECT_EQ(summary_of(stats, 0).warnings.size(), 0u); // the background may touch the border
}

TEST(LabelStatistics, CountsOneVoxelThinPlaces)
{
    // A 1-voxel-thick sheet of 2 between 1 and 3 along x: every sheet voxel is thin; the 2-voxel-thick
    // slabs of 1 and 3 are not (each voxel has its own label on one side along x).
    LabelImage image({6, 4, 4}, {1, 1, 1});
    for (std::size_t k = 0; k < 4; ++k)
        for (std::size_t j = 0; j < 4; ++j) {
            image.at(0, j, k) = 1, image.at(1, j, k) = 1;
            image.at(2, j, k) = 2;
            image.at(3, j, k) = 3, image.at(4, j, k) = 3, image.at(5, j, k) = 3;
        }
    const LabelStatistics stats = analyze_labels(image);
    EXPECT_EQ(summary_of(stats, 2).thin_voxels, 16u);
    EXPECT_EQ(summary_of(stats, 1).thin_voxels, 0u);
    EXPECT_EQ(summary_of(stats, 3).thin_voxels, 0u);
}

TEST(LabelStatistics, FlagsTheOneVoxelShellOfTheThinPhantom)
{
    // A one-voxel shell sampled on a grid is one piece through corners (26) but breaks through faces (6)
    // where it crosses voxel rows diagonally; most of its voxels have other tissues on both sides. The
    // thick ball and the background have no thin voxels.
    const Phantom phantom = make_phantom("thin", {.voxel_mm = 1.0});
    const LabelStatistics stats = analyze_labels(phantom.image);
    const LabelSummary& shell = summary_of(stats, 1);
    EXPECT_EQ(shell.components26, 1u);
    EXPECT_GT(shell.components6, 1u);
    EXPECT_GT(shell.thin_voxels, shell.voxels / 2);
    EXPECT_EQ(summary_of(stats, 2).thin_voxels, 0u);
    EXPECT_EQ(summary_of(stats, 0).thin_voxels, 0u);
    EXPECT_EQ(summary_of(stats, 2).touches, (std::vector<Label>{1})); // the shell is closed through faces
}

TEST(LabelStatistics, FindsTinyIslands)
{
    // Label 1: one 8-voxel block plus two single voxels; with a threshold of 5 voxels the two singles
    // are islands and the block is not.
    LabelImage image({8, 8, 8}, {1, 1, 1});
    for (std::size_t k = 1; k < 3; ++k)
        for (std::size_t j = 1; j < 3; ++j)
            for (std::size_t i = 1; i < 3; ++i) image.at(i, j, k) = 1;
    image.at(5, 5, 5) = 1;
    image.at(6, 2, 5) = 1;
    const LabelStatistics stats = analyze_labels(image, {.island_voxels = 5});
    const LabelSummary& s = summary_of(stats, 1);
    EXPECT_EQ(s.components6, 3u);
    EXPECT_EQ(s.islands, 2u);
    EXPECT_EQ(s.island_voxels, 2u);
    bool warned = false;
    for (const auto& w : s.warnings) warned |= w.find("2 islands under 5 voxels") != std::string::npos;
    EXPECT_TRUE(warned);
}

TEST(LabelStatistics, ComponentsPartitionTheImage)
{
    const Phantom phantom = make_phantom("junction", {.voxel_mm = 2});
    for (const auto connectivity : {Connectivity::faces6, Connectivity::full26}) {
        const Components components = find_components(phantom.image, connectivity);
        std::size_t total = 0;
        for (const std::size_t size : components.size) total += size;
        EXPECT_EQ(total, phantom.image.voxel_count());
        for (std::size_t v = 0; v < phantom.image.voxel_count(); ++v)
            ASSERT_EQ(components.label[components.component[v]], phantom.image.labels()[v]);
        // Every tissue of this phantom is one solid piece; the background too.
        EXPECT_EQ(components.count(), 4u);
    }
}

TEST(LabelStatistics, DescribesGridAndOrientation)
{
    EXPECT_EQ(orientation_code(identity_matrix()), "RAS");
    EXPECT_EQ(orientation_code({-1, 0, 0, 0, -1, 0, 0, 0, 1}), "LPS");
    EXPECT_EQ(orientation_code({0, 0, 1, -1, 0, 0, 0, 1, 0}), "PSR"); // i -> -y, j -> +z, k -> +x
    const Phantom phantom = make_phantom("spheres4", {.voxel_mm = 4});
    const LabelStatistics stats = analyze_labels(phantom.image);
    EXPECT_EQ(stats.dims, phantom.image.dims());
    EXPECT_EQ(stats.labels.size(), 5u);
    EXPECT_EQ(summary_of(stats, 1).name, "scalp");
    EXPECT_EQ(summary_of(stats, 0).warnings.size(), 0u);
    EXPECT_EQ(summary_of(stats, 1).border_voxels, 0u);
    EXPECT_EQ(summary_of(stats, 1).touches, (std::vector<Label>{0, 2}));
    // The 2 mm CSF layer is thinner than a 4 mm voxel, so the brain meets the skull through its gaps.
    EXPECT_EQ(summary_of(stats, 4).touches, (std::vector<Label>{2, 3}));
    EXPECT_GT(summary_of(stats, 3).thin_voxels, 0u);
}

TEST(LabelStatistics, HeadSampleHasTheDocumentedVoxelCounts)
{
    const LabelImage head = io::read_label_image(testing::data_path("samples/usc19-5_head.nii.gz"));
    const LabelStatistics stats = analyze_labels(head);
    std::ifstream sidecar(testing::data_path("samples/usc19-5_head.json"));
    const auto expected = nlohmann::json::parse(sidecar).at("voxel_counts");
    ASSERT_EQ(stats.labels.size(), 7u);
    for (const auto& s : stats.labels) EXPECT_EQ(s.voxels, expected.at(std::to_string(s.label)).get<std::size_t>());
    // The scalp reaches the image border in this sample (its bounding box starts at slice 0).
    EXPECT_GT(summary_of(stats, 1).border_voxels, 0u);
}

TEST(LabelStatistics, RejectsEmptyImage) { EXPECT_THROW(analyze_labels(LabelImage{}), InputError); }

} // namespace
} // namespace tissuemesh::image

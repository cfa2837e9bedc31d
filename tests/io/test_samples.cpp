// The shipped samples read with the geometry and label content their provenance files state.
#include <fstream>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/read_label_image.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

using testing::read_json;

TEST(Samples, TorsoWorldCoordinatesMatchTheNiftiAffine)
{
    const LabelImage image = io::read_label_image(testing::data_path("samples/totalseg_torso_3mm.nii.gz"));
    const auto affine = read_json(testing::data_path("samples/totalseg_torso_3mm_withbody.json"))["nifti_affine"];
    EXPECT_EQ(image.dims(), (Dims{122, 101, 112}));
    for (const Vec3& index : {Vec3{0, 0, 0}, Vec3{121, 0, 0}, Vec3{10, 20, 30}, Vec3{121, 100, 111}}) {
        const Vec3 world = image.index_to_world(index);
        for (int row = 0; row < 3; ++row) {
            double expected = affine[row][3].get<double>();
            for (int column = 0; column < 3; ++column) expected += affine[row][column].get<double>() * index[column];
            // The affine is stored as float32 in the file and as its exact decimal in the JSON: 1e-4 mm.
            EXPECT_NEAR(world[row], expected, 1e-4) << "index " << index[0] << "," << index[1] << "," << index[2];
        }
    }
}

TEST(Samples, LiverInrimageHasHeaderSpacingAndItsFiveLabels)
{
    const LabelImage image = io::read_label_image(testing::data_path("samples/liver.inr.gz"));
    EXPECT_EQ(image.dims(), (Dims{438, 353, 165}));
    // The header says VX=0.617188 VY=0.617188 VZ=1.33333: compare to those digits.
    EXPECT_NEAR(image.spacing_mm()[0], 0.617188, 1e-6);
    EXPECT_NEAR(image.spacing_mm()[1], 0.617188, 1e-6);
    EXPECT_NEAR(image.spacing_mm()[2], 1.33333, 1e-5);
    std::set<Label> labels;
    for (const auto& [label, count] : count_labels(image)) labels.insert(label);
    EXPECT_EQ(labels, (std::set<Label>{0, 84, 85, 127, 255}));
}

TEST(Samples, HeadVoxelCountsMatchTheSidecar)
{
    const auto sidecar = testing::data_path("samples/usc19-5_head.json");
    const LabelImage image =
        io::read_label_image(testing::data_path("samples/usc19-5_head.nii.gz"), {.names_json = sidecar});
    EXPECT_EQ(image.dims(), (Dims{166, 209, 223}));
    const auto expected = read_json(sidecar)["voxel_counts"];
    const auto counts = count_labels(image);
    ASSERT_EQ(counts.size(), expected.size());
    for (const auto& [label, count] : counts)
        EXPECT_EQ(count, expected[std::to_string(label)].get<std::size_t>()) << "label " << label;
    EXPECT_EQ(image.name_of(4), "grey matter");
    EXPECT_EQ(image.names().size(), 7u);
}

TEST(TissueNames, ReadsPlainTablesAndLabelsKey)
{
    testing::TempDir dir;
    std::ofstream(dir / "plain.json") << R"({"1": "scalp", "65535": "implant"})";
    const TissueNames plain = io::read_tissue_names(dir / "plain.json");
    EXPECT_EQ(plain, (TissueNames{{1, "scalp"}, {65535, "implant"}}));
    const TissueNames sidecar = io::read_tissue_names(testing::data_path("samples/usc19-5_head.json"));
    EXPECT_EQ(sidecar.at(6), "air cavities");
}

} // namespace
} // namespace tissuemesh

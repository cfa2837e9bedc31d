// tm-phantom and tm-info run as a user runs them.
#include <algorithm>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/read_label_image.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

using testing::read_json;
using testing::run_cli;
using testing::TempDir;

TEST(PhantomCli, WritesImageGeometryAndTissueNames)
{
    TempDir dir;
    const auto result = run_cli("tm-phantom", {"spheres4", "--voxel-mm", "4", "-o", (dir / "s4.nii.gz").string(),
                                               "--json", (dir / "phantom.json").string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(dir.files(),
              (std::vector<std::string>{"phantom.json", "s4.geometry.json", "s4.labels.json", "s4.nii.gz"}));
    const LabelImage image = io::read_label_image(dir / "s4.nii.gz");
    EXPECT_EQ(image.dims(), (Dims{50, 50, 50})); // 2 * ceil(92 / 4) + 4
    EXPECT_DOUBLE_EQ(image.spacing_mm()[0], 4.0);
    const TissueNames names = io::read_tissue_names(dir / "s4.labels.json");
    EXPECT_EQ(names.at(1), "scalp");
    EXPECT_EQ(names.at(4), "brain");
    const auto geometry = read_json(dir / "s4.geometry.json");
    EXPECT_EQ(geometry.at("phantom"), "spheres4");
    EXPECT_EQ(geometry.at("geometry").at("shapes").at(0).at("radius"), 92.0);
    const auto summary = read_json(dir / "phantom.json");
    EXPECT_EQ(summary.at("status"), "ok");
    const auto counts = count_labels(image);
    EXPECT_EQ(summary.at("tissues").at("2").at("voxels").get<std::size_t>(), counts.at(2));
}

TEST(PhantomCli, ListsPhantomsAndRejectsUnknownOnes)
{
    const auto list = run_cli("tm-phantom", {"--list"});
    EXPECT_EQ(list.exit_code, 0);
    for (const char* name : {"spheres4", "junction", "thin", "boxes", "ellipsoids"})
        EXPECT_NE(list.out.find(name), std::string::npos) << name;
    TempDir dir;
    const auto bad = run_cli("tm-phantom", {"sphere", "-o", (dir / "x.nii.gz").string()});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_EQ(bad.err, "tm-phantom: error: unknown phantom 'sphere'; choose one of: spheres4, junction, thin, "
                       "boxes, ellipsoids\n");
    EXPECT_TRUE(dir.files().empty());
    const auto zero = run_cli("tm-phantom", {"thin", "--voxel-mm", "0", "-o", (dir / "x.nii.gz").string()});
    EXPECT_EQ(zero.exit_code, 2);
    EXPECT_NE(zero.err.find("voxel size 0 mm"), std::string::npos) << zero.err;
    EXPECT_TRUE(dir.files().empty());
}

TEST(InfoCli, PrintsLabelsOfAPhantom)
{
    TempDir dir;
    ASSERT_EQ(run_cli("tm-phantom", {"junction", "--voxel-mm", "2", "-o", (dir / "j.nii.gz").string(), "-q"}).exit_code,
              0);
    const auto result = run_cli("tm-info", {"-i", (dir / "j.nii.gz").string(), "--labels",
                                            (dir / "j.labels.json").string(), "--json", (dir / "info.json").string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    for (const char* name : {"shell", "lower_half", "upper_half", "orientation RAS"})
        EXPECT_NE(result.out.find(name), std::string::npos) << name << "\n" << result.out;
    const auto info = read_json(dir / "info.json");
    EXPECT_EQ(info.at("labels").size(), 4u);
    EXPECT_EQ(info.at("labels").at(2).at("touches"), (nlohmann::json{1, 3})); // lower half: shell, upper half
}

TEST(InfoCli, HeadSummaryHasTheSevenVoxelCounts)
{
    TempDir dir;
    const auto result = run_cli("tm-info", {testing::data_path("samples/usc19-5_head.nii.gz").string(), "--json",
                                            (dir / "info.json").string(), "-q"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const auto info = read_json(dir / "info.json");
    std::ifstream sidecar(testing::data_path("samples/usc19-5_head.json"));
    const auto expected = nlohmann::json::parse(sidecar).at("voxel_counts");
    EXPECT_EQ(info.at("voxel_counts"), expected);
    EXPECT_NE(result.out.find("on the image border"), std::string::npos); // the scalp is cut at slice 0
}

TEST(InfoCli, MissingFileExitsTwoWithOneLine)
{
    TempDir dir;
    const auto result = run_cli("tm-info", {"-i", (dir / "absent.nii.gz").string()});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_EQ(result.err.rfind("tm-info: error: ", 0), 0u) << result.err;
    EXPECT_NE(result.err.find("absent.nii.gz"), std::string::npos) << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1);
}

} // namespace
} // namespace tissuemesh

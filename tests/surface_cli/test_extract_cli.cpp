// tm-extract as a user runs it: outputs, per-tissue surfaces, JSON summary, and failures.
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "image/phantom.h"
#include "io/surface_io.h"
#include "io/write_label_image.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

using testing::run_cli;
using testing::TempDir;

/// A 6x5x4 image: tissue 1 box with a tissue 2 block inside touching one face, tissue 3 voxel apart.
LabelImage small_image()
{
    LabelImage image({6, 5, 4}, {1.5, 1.5, 2.0}, {10, -20, 30});
    for (std::size_t k = 0; k < 4; ++k)
        for (std::size_t j = 0; j < 5; ++j)
            for (std::size_t i = 0; i < 6; ++i) image.at(i, j, k) = static_cast<Label>(i < 2 ? 2 : (j < 4 ? 1 : 0));
    image.at(5, 4, 3) = 3;
    return image;
}

/// Every tissue's outward surface: every edge used once in each direction.
bool closed_per_tissue(const InterfaceComplex& complex, Label tissue)
{
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (std::size_t t = 0; t < complex.triangles.size(); ++t) {
        if (complex.sides[t].from != tissue && complex.sides[t].to != tissue) continue;
        Triangle tri = complex.triangles[t];
        if (complex.sides[t].to == tissue) std::swap(tri[1], tri[2]);
        for (int e = 0; e < 3; ++e) ++directed[{tri[e], tri[(e + 1) % 3]}];
    }
    for (const auto& [edge, count] : directed) {
        const auto reverse = directed.find({edge.second, edge.first});
        if (count != 1 || reverse == directed.end() || reverse->second != 1) return false;
    }
    return !directed.empty();
}

TEST(ExtractCli, WritesAValidPlyPerTissueSurfacesAndSummary)
{
    TempDir dir;
    io::write_label_image(small_image(), dir / "small.nii.gz");
    std::ofstream(dir / "names.json") << R"({"1": "scalp", "2": "skull", "3": "brain"})";
    const auto result = run_cli("tm-extract", {"-i", (dir / "small.nii.gz").string(), "-o", (dir / "out.ply").string(),
                                               "--labels", (dir / "names.json").string(), "--per-tissue",
                                               (dir / "tissues").string(), "--json", (dir / "summary.json").string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const InterfaceComplex complex = io::read_surface(dir / "out.ply");
    for (const int tissue : {0, 1, 2, 3}) EXPECT_TRUE(closed_per_tissue(complex, static_cast<Label>(tissue))) << tissue;
    EXPECT_EQ(complex.names.at(2), "skull");
    for (const char* name : {"1_scalp.stl", "2_skull.stl", "3_brain.stl"}) {
        const InterfaceComplex tissue = io::read_surface(dir / "tissues" / name);
        EXPECT_TRUE(closed_per_tissue(tissue, 1)) << name << " is one closed surface";
    }
    std::ifstream in(dir / "summary.json");
    const nlohmann::json summary = nlohmann::json::parse(in);
    EXPECT_EQ(summary["triangles"].get<std::size_t>(), complex.triangle_count());
    EXPECT_EQ(summary["tissues"]["3"]["voxels"].get<int>(), 1);
    EXPECT_GT(summary["tissues"]["1"]["junction_edges"].get<int>(), 0) << "1, 2 and background meet";
}

TEST(ExtractCli, TissueSelectionMergesTheRestIntoBackground)
{
    TempDir dir;
    io::write_label_image(small_image(), dir / "small.nii.gz");
    const auto result = run_cli("tm-extract", {"-i", (dir / "small.nii.gz").string(), "-o", (dir / "out.vtp").string(),
                                               "--tissues", "2,3", "-q"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const InterfaceComplex complex = io::read_surface(dir / "out.vtp");
    for (const LabelPair& side : complex.sides) {
        EXPECT_NE(side.from, 1);
        EXPECT_EQ(side.to, 0) << "2 and 3 only meet the background once 1 is merged into it";
    }
}

TEST(ExtractCli, PriorityKeepsAOneVoxelShellBetweenBallAndOutside)
{
    // The "thin" phantom at 2 mm: without a priority the ball touches the outside through the diagonal
    // gaps of its one-voxel shell; with the shell (named via --labels) prioritized it never does.
    TempDir dir;
    io::write_label_image(image::make_phantom("thin", {.voxel_mm = 2.0}).image, dir / "thin.nii.gz");
    std::ofstream(dir / "names.json") << R"({"1": "shell", "2": "ball"})";
    const auto ball_meets_outside = [&](const std::vector<std::string>& extra) {
        std::vector<std::string> args{"-i", (dir / "thin.nii.gz").string(), "-o", (dir / "out.ply").string(),
                                      "--labels", (dir / "names.json").string(), "--json", (dir / "s.json").string()};
        args.insert(args.end(), extra.begin(), extra.end());
        const auto result = run_cli("tm-extract", args);
        EXPECT_EQ(result.exit_code, 0) << result.err;
        std::size_t count = 0;
        for (const LabelPair& side : io::read_surface(dir / "out.ply").sides) count += side.from == 2 && side.to == 0;
        return count;
    };
    EXPECT_GT(ball_meets_outside({}), 0u);
    EXPECT_EQ(ball_meets_outside({"--priority", "shell=1"}), 0u);
    std::ifstream in(dir / "s.json");
    EXPECT_EQ(nlohmann::json::parse(in)["priority"]["1"].get<int>(), 1);
}

TEST(ExtractCli, BadInputExitsTwoWithOneLineAndNoOutput)
{
    TempDir dir;
    std::ofstream(dir / "broken.nii.gz") << "not an image";
    io::write_label_image(small_image(), dir / "small.nii.gz");
    const struct {
        std::vector<std::string> args;
        std::string hint;
    } cases[] = {
        {{"-i", (dir / "broken.nii.gz").string(), "-o", (dir / "out.ply").string()}, "broken.nii.gz"},
        {{"-i", (dir / "missing.nii.gz").string(), "-o", (dir / "out.ply").string()}, "missing.nii.gz"},
        {{"-i", (dir / "small.nii.gz").string(), "-o", (dir / "out.stl").string()}, ".ply or .vtp"},
        {{"-i", (dir / "small.nii.gz").string(), "-o", (dir / "out.ply").string(), "--tissues", "7"}, "tissue 7"},
        {{"-i", (dir / "small.nii.gz").string(), "-o", (dir / "out.ply").string(), "--tissues", "1",
          "--background", "1"}, "background"},
        {{"-i", (dir / "small.nii.gz").string(), "-o", (dir / "out.ply").string(), "--priority", "bone=1"},
         "--priority bone=1"},
        {{"-i", (dir / "small.nii.gz").string(), "-o", (dir / "out.ply").string(), "--priority", "7=1"},
         "priority given for label 7"},
    };
    for (const auto& c : cases) {
        const auto result = run_cli("tm-extract", c.args);
        EXPECT_EQ(result.exit_code, 2) << c.hint << ": " << result.err;
        EXPECT_NE(result.err.find("tm-extract: error: "), std::string::npos) << result.err;
        EXPECT_NE(result.err.find(c.hint), std::string::npos) << result.err;
        EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << "one line: " << result.err;
    }
    EXPECT_EQ(dir.files(), (std::vector<std::string>{"broken.nii.gz", "small.nii.gz"})) << "no output left behind";
}

} // namespace
} // namespace tissuemesh

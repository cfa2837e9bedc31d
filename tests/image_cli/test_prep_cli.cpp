// tm-prep run as a user runs it: good runs change what they say, bad options leave nothing behind.
#include <algorithm>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/read_label_image.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

using testing::run_cli;
using testing::TempDir;

/// A junction phantom (labels 0..3) at 2 mm in `dir`.
std::string make_input(const TempDir& dir)
{
    const std::string path = (dir / "in.nii.gz").string();
    EXPECT_EQ(run_cli("tm-phantom", {"junction", "--voxel-mm", "2", "-o", path, "-q"}).exit_code, 0);
    return path;
}

std::size_t lines(const std::string& text)
{
    return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST(PrepCli, RelabelsCropsAndReportsEachStep)
{
    TempDir dir;
    const std::string input = make_input(dir);
    const auto result = run_cli("tm-prep", {"-i", input, "-o", (dir / "out.nii.gz").string(), "--crop-pad", "1",
                                            "--relabel", "3:2", "--json", (dir / "prep.json").string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.err.find("[relabel] 3 -> 2"), std::string::npos) << result.err;
    const LabelImage in = io::read_label_image(input);
    const LabelImage out = io::read_label_image(dir / "out.nii.gz");
    const auto before = count_labels(in), after = count_labels(out);
    EXPECT_FALSE(after.contains(3));
    EXPECT_EQ(after.at(2), before.at(2) + before.at(3));
    EXPECT_EQ(after.at(1), before.at(1));
    // Cropped to the shell's box plus one voxel: the shell (radius 40 mm) spans 40 voxels of 2 mm.
    EXPECT_EQ(out.dims()[0], 40u + 2u);
    std::ifstream json(dir / "prep.json");
    const auto summary = nlohmann::json::parse(json);
    ASSERT_EQ(summary.at("steps").size(), 2u);
    EXPECT_EQ(summary.at("steps").at(0).at("step"), "relabel"); // the fixed order, not the flags' order
    EXPECT_EQ(summary.at("steps").at(1).at("step"), "crop-pad");
    EXPECT_EQ(summary.at("steps").at(0).at("changed_voxels").get<std::size_t>(), before.at(3));
}

TEST(PrepCli, CarriesTissueNamesThroughRelabel)
{
    TempDir dir;
    const std::string input = make_input(dir);
    const auto result = run_cli("tm-prep", {"-i", input, "--labels", (dir / "in.labels.json").string(), "-o",
                                            (dir / "out.nii.gz").string(), "--merge", "2,3", "-q"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const TissueNames names = io::read_tissue_names(dir / "out.labels.json");
    EXPECT_EQ(names, (TissueNames{{0, "background"}, {1, "shell"}, {2, "lower_half"}}));
}

TEST(PrepCli, UnknownLabelInRelabelExitsTwoAndWritesNothing)
{
    TempDir dir;
    const std::string input = make_input(dir);
    const auto before = dir.files();
    const auto result = run_cli("tm-prep", {"-i", input, "-o", (dir / "out.nii.gz").string(), "--relabel", "9:1"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_EQ(result.err,
              concat("tm-prep: error: --relabel: ", input, " has no tissue 9; its tissues are 0, 1, 2, 3\n"));
    EXPECT_EQ(dir.files(), before);
}

TEST(PrepCli, BadSpacingAndSyntaxExitTwoWithOneLine)
{
    TempDir dir;
    const std::string input = make_input(dir);
    const auto before = dir.files();
    const std::string out = (dir / "out.nii.gz").string();
    const auto zero = run_cli("tm-prep", {"-i", input, "-o", out, "--spacing-mm", "0"});
    EXPECT_EQ(zero.exit_code, 2);
    EXPECT_NE(zero.err.find("spacing 0 mm along axis 0: it must be a positive number"), std::string::npos) << zero.err;
    EXPECT_EQ(lines(zero.err), 1u) << zero.err;
    const auto syntax = run_cli("tm-prep", {"-i", input, "-o", out, "--relabel", "5-4"});
    EXPECT_EQ(syntax.exit_code, 2);
    EXPECT_NE(syntax.err.find("--relabel: '5-4' is not FROM:TO"), std::string::npos) << syntax.err;
    const auto range = run_cli("tm-prep", {"-i", input, "-o", out, "--keep-largest", "1,70000"});
    EXPECT_EQ(range.exit_code, 2);
    EXPECT_NE(range.err.find("--keep-largest: tissue 70000 is not a label number; labels are 0..65535"),
              std::string::npos)
        << range.err;
    EXPECT_EQ(dir.files(), before);
}

// Issue 32: tm-prep parsed its tissue arguments itself (numbers only, its own range check, no names).
TEST(PrepCli, TmPrepParsesTissueArgumentsItselfNoMore)
{
    TempDir dir;
    const std::string input = make_input(dir), labels = (dir / "in.labels.json").string();
    const std::string out = (dir / "out.nii.gz").string();
    const auto before = dir.files();
    // Names in any case, for every tissue option; --relabel's TO may be a new label, named by later steps.
    const auto named =
        run_cli("tm-prep", {"-i", input, "--labels", labels, "-o", out, "--merge", "Lower_Half,3", "--relabel",
                            "SHELL:7", "--keep-largest", "7", "--fill-holes-in", "lower_half", "-q"});
    ASSERT_EQ(named.exit_code, 0) << named.err;
    const auto after = count_labels(io::read_label_image(out));
    EXPECT_FALSE(after.contains(1));
    EXPECT_TRUE(after.contains(7));
    EXPECT_FALSE(after.contains(3)) << "merged into lower_half (2)";
    std::filesystem::remove(out), std::filesystem::remove(dir / "out.labels.json");
    // An unknown name lists the known tissues; a number out of range says the range instead of wrapping.
    const auto unknown = run_cli("tm-prep", {"-i", input, "--labels", labels, "-o", out, "--keep-largest", "liver"});
    EXPECT_EQ(unknown.exit_code, 2);
    EXPECT_NE(unknown.err.find("--keep-largest: unknown tissue \"liver\""), std::string::npos) << unknown.err;
    EXPECT_NE(unknown.err.find("1 shell"), std::string::npos) << "the known tissues are listed: " << unknown.err;
    const auto wrapped = run_cli("tm-prep", {"-i", input, "-o", out, "--merge", "2,65539"});
    EXPECT_EQ(wrapped.exit_code, 2);
    EXPECT_NE(wrapped.err.find("--merge: tissue 65539 is not a label number; labels are 0..65535"), std::string::npos)
        << wrapped.err;
    const auto to_range = run_cli("tm-prep", {"-i", input, "-o", out, "--relabel", "3:65536"});
    EXPECT_EQ(to_range.exit_code, 2);
    EXPECT_NE(to_range.err.find("tissue 65536 is not a label number"), std::string::npos) << to_range.err;
    EXPECT_EQ(dir.files(), before);
}

TEST(PrepCli, UnwritableOutputExitsTwoAndLeavesNothing)
{
    TempDir dir;
    const std::string input = make_input(dir);
    const auto before = dir.files();
    const auto result = run_cli("tm-prep", {"-i", input, "-o", (dir / "missing" / "out.nii.gz").string()});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_EQ(result.err.rfind("tm-prep: error: ", 0), 0u) << result.err;
    EXPECT_EQ(lines(result.err), 1u) << result.err;
    EXPECT_EQ(dir.files(), before);
    EXPECT_FALSE(std::filesystem::exists(dir / "missing"));
    const auto phantom = run_cli("tm-phantom", {"thin", "-o", (dir / "missing" / "t.nii.gz").string()});
    EXPECT_EQ(phantom.exit_code, 2);
    EXPECT_EQ(dir.files(), before);
}

TEST(PrepCli, CleansTheHeadSoNoTissueTouchesTheBorder)
{
    TempDir dir;
    const std::string out = (dir / "head.nii.gz").string();
    const auto prep = run_cli("tm-prep", {"-i", testing::data_path("samples/usc19-5_head.nii.gz").string(), "-o", out,
                                          "--remove-islands", "20", "--crop-pad", "2", "-q"});
    ASSERT_EQ(prep.exit_code, 0) << prep.err;
    const auto info = run_cli("tm-info", {"-i", out, "--island-voxels", "20", "--json", (dir / "info.json").string()});
    ASSERT_EQ(info.exit_code, 0) << info.err;
    std::ifstream json(dir / "info.json");
    const auto summary = nlohmann::json::parse(json);
    ASSERT_EQ(summary.at("labels").size(), 7u);
    for (const auto& label : summary.at("labels")) {
        if (label.at("label") == 0) continue;
        EXPECT_EQ(label.at("border_voxels"), 0) << label.at("label");
        EXPECT_EQ(label.at("islands"), 0) << label.at("label");
    }
}

} // namespace
} // namespace tissuemesh

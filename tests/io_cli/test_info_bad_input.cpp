// Bad label images through the program a user runs: tm-info exits 2 with one line on stderr that
// names the file and the problem.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "tests/io/make_test_images.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

struct BadFile {
    std::string name;                 ///< file the error line names, inside the temporary folder
    std::vector<std::string> message; ///< parts the error line must contain (after "<name>: ")
    std::string input = {};           ///< file given to tm-info when it is not `name` (a raw file's sidecar)
};

/// Runs tm-info on `file` and checks exit code 2 and a single error line naming the file and problem.
void expect_rejected(const testing::TempDir& dir, const BadFile& file)
{
    const std::string input = file.input.empty() ? file.name : file.input;
    const testing::CliResult result = testing::run_cli("tm-info", {"-i", (dir / input).string()});
    EXPECT_EQ(result.exit_code, 2) << file.name << "\n" << result.err;
    std::istringstream lines(result.err);
    std::string line, error_line;
    int error_lines = 0;
    while (std::getline(lines, line))
        if (line.find("error:") != std::string::npos) {
            error_line = line;
            ++error_lines;
        }
    EXPECT_EQ(error_lines, 1) << result.err;
    EXPECT_NE(error_line.find(file.name + ": "), std::string::npos) << error_line;
    for (const std::string& part : file.message) EXPECT_NE(error_line.find(part), std::string::npos) << error_line;
}

using testing::write_text;

testing::NiftiSpec with_spacing(float value)
{
    testing::NiftiSpec spec;
    spec.spacing[0] = value;
    return spec;
}

TEST(InfoBadInput, ReadsAValidFileAndExitsZero)
{
    testing::TempDir dir;
    testing::write_nifti(dir / "ok.nii", {}, {0, 1, 2, 3, 4, 5, 6, 7});
    const testing::CliResult result = testing::run_cli("tm-info", {"-i", (dir / "ok.nii").string()});
    EXPECT_EQ(result.exit_code, 0) << result.err;
}

/// A --json summary that cannot be written is an error: exit 2 and one line naming the file, not 0.
TEST(InfoBadInput, AnUnwritableJsonSummaryIsAnError)
{
    testing::TempDir dir;
    testing::write_nifti(dir / "ok.nii", {}, {0, 1, 2, 3, 4, 5, 6, 7});
    const std::string json = (dir / "no" / "such" / "x.json").string();
    const testing::CliResult result = testing::run_cli("tm-info", {"-i", (dir / "ok.nii").string(), "--json", json});
    EXPECT_EQ(result.exit_code, 2) << result.err;
    EXPECT_NE(result.err.find("x.json"), std::string::npos) << result.err;
    EXPECT_FALSE(std::filesystem::exists(json));
}

TEST(InfoBadInput, ExitsTwoWithOneLineNamingFileAndProblem)
{
    testing::TempDir dir;
    const std::vector<unsigned char> eight{0, 1, 2, 3, 4, 5, 6, 7};
    testing::write_bytes(dir / "empty.nii.gz", {});
    testing::write_nifti(dir / "short.nii", {}, {0, 1, 2});
    testing::NiftiSpec magic;
    magic.magic[1] = 'x';
    testing::write_nifti(dir / "magic.nii", magic, eight);
    testing::write_nifti(dir / "zero.nii", with_spacing(0), eight);
    testing::write_nifti(dir / "negative.nii", with_spacing(-2), eight);
    testing::write_nifti(dir / "nan.nii", with_spacing(std::nanf("")), eight);
    testing::NiftiSpec huge;
    huge.dims[1] = huge.dims[2] = huge.dims[3] = 30000;
    testing::write_nifti(dir / "huge.nii", huge, eight);
    testing::NiftiSpec float_spec;
    float_spec.datatype = 16;
    float_spec.bitpix = 32;
    testing::write_nifti(dir / "fraction.nii", float_spec, testing::voxel_bytes<float>({0, 1, 2, 3, 4, 5, 6, 1.5f}));
    testing::NiftiSpec int_spec;
    int_spec.datatype = 8;
    int_spec.bitpix = 32;
    testing::write_nifti(dir / "large.nii", int_spec, testing::voxel_bytes<std::int32_t>({0, 1, 2, 3, 4, 5, 6, 70000}));
    testing::write_nifti(dir / "minus.nii", int_spec, testing::voxel_bytes<std::int32_t>({0, -5, 2, 3, 4, 5, 6, 7}));
    testing::NiftiSpec vector;
    vector.vectors = 3;
    testing::write_nifti(dir / "vector.nii", vector, std::vector<unsigned char>(24, 1));
    std::string inr = "#INRIMAGE-4#{\nXDIM=2\nYDIM=2\nZDIM=2\nVDIM=1\nTYPE=unsigned fixed\nPIXSIZE=8 bits\n";
    inr.append(252 - inr.size(), '\n');
    write_text(dir / "short.inr", inr + "##}\n\1\2");
    write_text(dir / "over.json", R"({"dims": [4000000000, 4000000000, 4000000000], "spacing": [1, 1, 1],
                                      "dtype": "uint8", "raw_file": "short.raw"})");
    write_text(dir / "short.raw", "\1\2\3");
    write_text(dir / "short.json",
               R"({"dims": [2, 2, 2], "spacing": [1, 1, 1], "dtype": "uint8", "raw_file": "short.raw"})");
    write_text(dir / "head.png", "not an image");

    const std::vector<BadFile> cases{
        {"missing.nii.gz", {"no such file"}},
        {"empty.nii.gz", {"the file is empty"}},
        {"short.nii", {"truncated", "need 8 bytes"}},
        {"short.inr", {"truncated", "holds 2"}},
        {"short.raw", {"truncated", "holds 3"}, "short.json"},
        {"magic.nii", {"not a NIfTI file", "magic"}},
        {"zero.nii", {"spacing along axis 0 is 0 mm"}},
        {"negative.nii", {"spacing along axis 0 is -2 mm"}},
        {"nan.nii", {"spacing along axis 0 is nan mm"}},
        {"over.json", {"dimensions 4000000000 x 4000000000 x 4000000000 overflow"}},
        {"huge.nii", {"truncated", "27000000000000 bytes"}},
        {"fraction.nii", {"voxel (1, 1, 1) holds 1.5", "whole numbers"}},
        {"large.nii", {"voxel (1, 1, 1) holds 70000", "0..65535"}},
        {"minus.nii", {"voxel (1, 0, 0) holds -5", "0..65535"}},
        {"vector.nii", {"3 values along axis 4", "one value per voxel"}},
        {"head.png", {"unknown image format '.png'"}},
    };
    for (const BadFile& file : cases) expect_rejected(dir, file);
}

TEST(InfoBadInput, BadTissueNameTable)
{
    testing::TempDir dir;
    testing::write_nifti(dir / "ok.nii", {}, {0, 1, 2, 3, 4, 5, 6, 7});
    write_text(dir / "names.json", R"({"scalp": "1"})");
    const testing::CliResult result =
        testing::run_cli("tm-info", {"-i", (dir / "ok.nii").string(), "--labels", (dir / "names.json").string()});
    EXPECT_EQ(result.exit_code, 2) << result.err;
    EXPECT_NE(result.err.find("names.json: tissue-name key 'scalp' is not a label number"), std::string::npos)
        << result.err;
}

} // namespace
} // namespace tissuemesh

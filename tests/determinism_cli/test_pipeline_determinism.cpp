// Determinism: the whole pipeline, run twice on the same phantom with one and with two threads allowed
// (OMP_NUM_THREADS, read by the solver's libraries), writes the same bytes in every output file.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/cli.h"

namespace tissuemesh::testing {
namespace {

std::string read_bytes(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The refinement log without its last column (seconds, which differ from run to run).
std::string without_timings(const std::string& csv)
{
    std::istringstream lines(csv);
    std::string result;
    for (std::string line; std::getline(lines, line);) result += line.substr(0, line.rfind(',')) + "\n";
    return result;
}

/// Runs every step from phantom to fields inside `dir`, with `threads` as OMP_NUM_THREADS. File names are
/// relative (the programs run in `dir`), since some outputs quote their input's name.
void run_pipeline(const TempDir& dir, const std::string& threads)
{
    ::setenv("OMP_NUM_THREADS", threads.c_str(), 1);
    const std::filesystem::path previous = std::filesystem::current_path();
    std::filesystem::current_path(dir.path());
    const auto at = [](const std::string& name) { return name; };
    std::ofstream(dir / "conductivity.json") << R"({"1": 0.43, "2": 0.33, "3": 0.14})";
    const std::vector<std::pair<std::string, std::vector<std::string>>> steps{
        {"tm-phantom", {"junction", "--voxel-mm", "3", "-o", at("image.nii.gz")}},
        {"tm-prep", {"-i", at("image.nii.gz"), "-o", at("clean.nii.gz"), "--remove-islands", "5", "--crop-pad", "2"}},
        {"tm-extract",
         {"-i", at("clean.nii.gz"), "--labels", at("image.labels.json"), "-o", at("interfaces.ply"), "--per-tissue",
          at("tissues")}},
        {"tm-smooth", {"-i", at("interfaces.ply"), "--image", at("clean.nii.gz"), "-o", at("smooth.ply")}},
        // Surface nets: extraction with its smoothing (Jacobi steps, checked on all threads), then decimated.
        {"tm-extract",
         {"-i", at("clean.nii.gz"), "--labels", at("image.labels.json"), "-o", at("nets.ply"), "--method",
          "surface-nets"}},
        // With the workflow's contraction before the collapses (3 mm voxels, blocks of 1.5 voxels).
        {"tm-decimate",
         {"-i", at("nets.ply"), "-o", at("nets-decimated.ply"), "--max-distance-mm", "1", "--slabs", "3",
          "--contract-blocks-mm", "4.5"}},
        // Decimation and remeshing in slabs (in parallel): the bytes must not depend on the threads.
        {"tm-decimate", {"-i", at("smooth.ply"), "-o", at("decimated.ply"), "--max-distance-mm", "1", "--slabs", "3"}},
        {"tm-remesh", {"-i", at("decimated.ply"), "-o", at("remeshed.ply"), "--edge-mm", "4", "--slabs", "2"}},
        {"tm-tetra", {"-i", at("remeshed.ply"), "-o", at("mesh.msh")}},
        {"tm-assess", {"-i", at("mesh.msh"), "--image", at("clean.nii.gz"), "-o", at("assessed.vtu")}},
        {"tm-refine",
         {"-i", at("mesh.msh"), "--image", at("clean.nii.gz"), "-o", at("refined.msh"), "--iterations", "2", "--log",
          at("refine.csv"), "--plot", at("refine.svg")}},
        {"tm-solve",
         {"-i", at("refined.msh"), "-o", at("fields.vtu"), "--conductivity", at("conductivity.json"), "--dipole",
          "0,0,0,0,0,1e-8", "--dipole", "5,-3,2,1e-8,0,0"}},
    };
    for (const auto& [tool, args] : steps) {
        std::vector<std::string> quiet = args;
        quiet.push_back("-q");
        const CliResult result = run_cli(tool, quiet);
        EXPECT_EQ(result.exit_code, 0) << tool << ": " << result.err;
        if (result.exit_code != 0) break;
    }
    std::filesystem::current_path(previous);
    ::unsetenv("OMP_NUM_THREADS");
}

std::vector<std::filesystem::path> output_files(const TempDir& dir)
{
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir.path()))
        if (entry.is_regular_file()) files.push_back(std::filesystem::relative(entry.path(), dir.path()));
    std::sort(files.begin(), files.end());
    return files;
}

TEST(PipelineDeterminism, SameBytesWithOneAndTwoThreads)
{
    TempDir one, two;
    ASSERT_NO_FATAL_FAILURE(run_pipeline(one, "1"));
    ASSERT_NO_FATAL_FAILURE(run_pipeline(two, "2"));
    ASSERT_FALSE(::testing::Test::HasFailure());
    const auto files = output_files(one);
    ASSERT_EQ(files, output_files(two));
    // phantom, prep, 1 complex + 3 tissue surfaces, 3 surface steps, mesh, assessed, refined, log, plot, fields.
    ASSERT_GE(files.size(), 15u);
    for (const auto& file : files) {
        const std::string a = read_bytes(one.path() / file), b = read_bytes(two.path() / file);
        EXPECT_GT(a.size(), 0u) << file;
        if (file.extension() == ".csv") EXPECT_EQ(without_timings(a), without_timings(b)) << file;
        else EXPECT_TRUE(a == b) << file << " differs between the runs";
    }
}

} // namespace
} // namespace tissuemesh::testing

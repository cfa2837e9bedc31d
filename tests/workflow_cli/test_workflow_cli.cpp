// data/workflows/Makefile on the boxes phantom at 4 mm: the whole chain to report.html, nothing redone by a
// second make, only the dependent steps redone when one parameter changes, and a cohort in parallel.
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <map>

#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

namespace fs = std::filesystem;
using testing::read_text;
using testing::run_cli;
using testing::run_program;
using testing::TempDir;

/// Modification times of the step summaries (each step's make target) in `out`.
std::map<std::string, fs::file_time_type> summary_times(const fs::path& out)
{
    std::map<std::string, fs::file_time_type> times;
    for (const auto& entry : fs::directory_iterator(out))
        if (entry.path().extension() == ".json" && entry.path().filename() != "clean.labels.json")
            times[entry.path().stem().string()] = entry.last_write_time();
    return times;
}

/// The steps whose summary changed between two snapshots.
std::vector<std::string> changed(const std::map<std::string, fs::file_time_type>& before,
                                 const std::map<std::string, fs::file_time_type>& after)
{
    std::vector<std::string> names;
    for (const auto& [name, time] : after)
        if (!before.count(name) || before.at(name) != time) names.push_back(name);
    return names;
}

class WorkflowCli : public ::testing::Test {
protected:
    void SetUp() override
    {
        const auto result =
            run_cli("tm-phantom", {"boxes", "--voxel-mm", "4", "-o", (dir / "boxes.nii.gz").string(), "-q"});
        ASSERT_EQ(result.exit_code, 0) << result.err;
    }
    /// make -C data/workflows with the small-phantom parameters and `extra` variables.
    testing::CliResult make(const std::vector<std::string>& extra, const std::string& out = "out")
    {
        std::vector<std::string> args{"-C",
                                      testing::data_path("workflows").string(),
                                      "IMAGE=" + (dir / "boxes.nii.gz").string(),
                                      "LABELS=" + (dir / "boxes.labels.json").string(),
                                      "OUT=" + (dir / out).string(),
                                      "BIN=" TM_TOOLS_DIR,
                                      "REMESH_EDGE_MM=6",
                                      "REFINE_ARGS=--iterations 2"};
        args.insert(args.end(), extra.begin(), extra.end());
        return run_program("make", args);
    }
    TempDir dir;
};

TEST_F(WorkflowCli, ChainsEveryStepAndRerunsOnlyWhatAParameterChanges)
{
    auto result = make({"-j2"});
    ASSERT_EQ(result.exit_code, 0) << result.out << result.err;
    const fs::path out = dir / "out";
    const auto first = summary_times(out);
    for (const char* step : {"prep", "extract", "decimate", "remesh", "tetra", "assess", "refine", "check-mesh",
                             "render-surface", "render-section", "render-quality", "render-convergence", "report"}) {
        ASSERT_TRUE(first.count(step)) << step;
        EXPECT_EQ(testing::read_json(out / (std::string(step) + ".json"))["status"], "ok") << step;
    }
    // Surface nets by default: tm-extract smooths, there is no smoothing step; decimation keeps edges below
    // 4/3 of the remeshing target.
    EXPECT_EQ(testing::read_json(out / "extract.json")["method"], "surface-nets");
    EXPECT_FALSE(first.count("smooth"));
    EXPECT_NEAR(testing::read_json(out / "decimate.json")["max_edge_mm"].get<double>(), 8.0, 1e-9);
    EXPECT_EQ(testing::read_json(out / "refine.json")["mode"], "constrained");
    EXPECT_EQ(testing::read_json(out / "refine.json")["iterations"].size(), 3u); // round 0 and 2 rounds
    const std::string html = read_text(out / "report.html");
    for (const char* tissue : {"cube", "box_a", "box_b"})
        EXPECT_NE(html.find(std::string("<td>") + tissue + "</td>"), std::string::npos) << tissue;
    for (const char* picture : {"surface", "section", "quality", "convergence"})
        EXPECT_NE(html.find(std::string("<figcaption>") + picture + "</figcaption>"), std::string::npos) << picture;

    // A second make does nothing.
    result = make({});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.out.find("Nothing to be done"), std::string::npos) << result.out;
    EXPECT_TRUE(changed(first, summary_times(out)).empty());

    // A picture parameter: that picture and the report.
    result = make({"RENDER_SECTION_ARGS=--axis x"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const auto second = summary_times(out);
    EXPECT_EQ(changed(first, second), (std::vector<std::string>{"render-section", "report"}));
    EXPECT_EQ(testing::read_json(out / "render-section.json")["axis"], "x");

    // A refinement parameter: refinement and everything after it, nothing before it.
    result = make({"RENDER_SECTION_ARGS=--axis x", "REFINE_ARGS=--iterations 1"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(changed(second, summary_times(out)),
              (std::vector<std::string>{"check-mesh", "refine", "render-convergence", "render-quality",
                                        "render-section", "report"}));
    EXPECT_EQ(testing::read_json(out / "refine.json")["iterations"].size(), 2u);

    // The earlier chain on request: marching cubes, then tm-smooth; everything from extraction on is redone.
    result = make({"RENDER_SECTION_ARGS=--axis x", "REFINE_ARGS=--iterations 1", "EXTRACT_METHOD=marching-cubes"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(testing::read_json(out / "extract.json")["method"], "marching-cubes");
    EXPECT_EQ(testing::read_json(out / "smooth.json")["status"], "ok");
    EXPECT_EQ(testing::read_json(out / "tetra.json")["status"], "ok");
}

TEST_F(WorkflowCli, CohortMeshesEverySubjectAndAMissingImageIsExplained)
{
    const fs::path subjects = dir / "subjects";
    fs::create_directory(subjects);
    fs::copy_file(dir / "boxes.nii.gz", subjects / "s01.nii.gz");
    fs::copy_file(dir / "boxes.nii.gz", subjects / "s02.nii.gz");
    const auto result =
        run_program("make", {"-C", testing::data_path("workflows").string(), "cohort", "-j2",
                             "COHORT=" + subjects.string(), "COHORT_OUT=" + (dir / "cohort").string(),
                             "BIN=" TM_TOOLS_DIR, "REMESH_ARGS=--edge-mm 6", "REFINE_ARGS=--iterations 1"});
    ASSERT_EQ(result.exit_code, 0) << result.out << result.err;
    EXPECT_NE(result.out.find("cohort: 2 subjects"), std::string::npos) << result.out;
    for (const char* subject : {"s01", "s02"}) {
        EXPECT_TRUE(fs::exists(dir / "cohort" / subject / "report.html")) << subject;
        EXPECT_EQ(testing::read_json(dir / "cohort" / subject / "check-mesh.json")["status"], "ok") << subject;
    }

    const auto missing =
        run_program("make", {"-C", testing::data_path("workflows").string(), "OUT=" + (dir / "x").string()});
    EXPECT_EQ(missing.exit_code, 2);
    EXPECT_NE(missing.err.find("IMAGE is not set"), std::string::npos) << missing.err;
}

/// Runs the ready-made target `preset` (make sphere-head, ...) into `out` with this build's programs.
/// make -C data/workflows with our tools, OUT=`out` and `arguments` (targets and variables); it must succeed.
void make_workflow(const std::vector<std::string>& arguments, const fs::path& out)
{
    std::vector<std::string> args{"-C", testing::data_path("workflows").string(), "OUT=" + out.string(),
                                  "BIN=" TM_TOOLS_DIR};
    args.insert(args.end(), arguments.begin(), arguments.end());
    const auto result = run_program("make", args);
    ASSERT_EQ(result.exit_code, 0) << result.out << result.err;
}

void make_preset(const std::string& preset, const fs::path& out) { make_workflow({preset}, out); }

TEST(WorkflowCliLong, SphereHeadEndsWithASolvedModelAndItsReport)
{
    // scripts/demo's target: about 7 min on 2 shared cores (smoothing 800 k triangles dominates).
    TempDir dir;
    ASSERT_NO_FATAL_FAILURE(make_preset("sphere-head", dir / "head"));
    const fs::path out = dir / "head";
    EXPECT_EQ(testing::read_json(out / "check-mesh.json")["ok"], true);
    EXPECT_EQ(testing::read_json(out / "solve.json")["status"], "ok");
    for (const char* tissue : {"1", "2", "3", "4"})
        EXPECT_GT(testing::read_json(out / "check-mesh.json")["tissues"][tissue]["dice"].get<double>(), 0.9);
    const std::string html = read_text(out / "report.html");
    for (const char* tissue : {"scalp", "skull", "csf", "brain"})
        EXPECT_NE(html.find(std::string("<td>") + tissue + "</td>"), std::string::npos);
    for (const char* picture : {"surface", "section", "quality", "convergence"})
        EXPECT_NE(html.find(std::string("<figcaption>") + picture + "</figcaption>"), std::string::npos) << picture;
    EXPECT_NE(html.find("<td>tm-solve</td>"), std::string::npos);
}

// The real head through the whole chain (the preset once stopped at the surfaces: tm-tetra refused TetGen's
// mesh of it). About 4 min on 2 shared cores. Every tissue keeps a Dice over 0.9 against the 2 mm voxels,
// and the tDCS solve converges.
TEST(WorkflowCliLong, Usc19HeadEndsWithAFemFitMeshAndASolvedModel)
{
    TempDir dir;
    ASSERT_NO_FATAL_FAILURE(make_preset("usc19-5-head", dir / "head"));
    const fs::path out = dir / "head";
    const auto check = testing::read_json(out / "check-mesh.json");
    EXPECT_EQ(check["ok"], true);
    EXPECT_EQ(check["unmarked_interfaces"], 0);
    // TetGen keeps every interface triangle; the improver then splits some where it adds nodes on interfaces
    // (this held interface faces equal to input triangles, which failed once the improver became the default).
    const auto tetra = testing::read_json(out / "tetra.json");
    EXPECT_EQ(tetra["split_interface_triangles"], 0);
    EXPECT_GE(tetra["interface_faces"].get<std::size_t>(), tetra["input_triangles"].get<std::size_t>());
    for (const char* tissue : {"1", "2", "3", "4", "5", "6"})
        EXPECT_GT(check["tissues"][tissue]["dice"].get<double>(), 0.9) << tissue;
    const auto solve = testing::read_json(out / "solve.json");
    EXPECT_EQ(solve["status"], "ok");
    EXPECT_LT(solve["relative_residual"].get<double>(), 1e-6);
    EXPECT_NE(read_text(out / "report.html").find("<td>tm-solve</td>"), std::string::npos);
}

/// The default workflow on a real volume, as ../shared/tools/real-heads runs it (IMAGE and LABELS, nothing else):
/// fit for FEM, and every tet at 10 degrees or more, the 1st percentile at 20 or more, after tm-tetra and after
/// tm-refine (issue 28's bounds). Measured 2026-12-06: torso 12.66 and 12.39 degrees, liver 20.03 and 15.47.
void expect_real_volume_meshed_well(const std::string& image, const std::string& labels,
                                    const std::vector<std::string>& more = {})
{
    TempDir dir;
    const fs::path out = dir / "out";
    std::vector<std::string> variables{"IMAGE=" + testing::data_path(image).string()};
    if (!labels.empty()) variables.push_back("LABELS=" + testing::data_path(labels).string());
    variables.insert(variables.end(), more.begin(), more.end());
    ASSERT_NO_FATAL_FAILURE(make_workflow(variables, out));
    EXPECT_EQ(testing::read_json(out / "check-mesh.json")["ok"], true);
    for (const char* step : {"tetra.json", "refine.json"}) {
        const auto after = testing::read_json(out / step)["improvement"]["after"];
        EXPECT_GE(after["min_dihedral_deg"].get<double>(), 10) << step;
        EXPECT_GE(after["p1_min_dihedral_deg"].get<double>(), 20) << step;
    }
}

// About 2 min on 2 idle cores.
TEST(WorkflowCliLong, TorsoMeshesWithEveryTetAtTenDegreesOrMore)
{
    expect_real_volume_meshed_well("samples/totalseg_torso_3mm.nii.gz", "samples/totalseg_torso_3mm_withbody.json");
}

// About 20 s on 2 idle cores.
TEST(WorkflowCliLong, LiverMeshesWithEveryTetAtTenDegreesOrMore)
{
    expect_real_volume_meshed_well("samples/liver.inr.gz", "");
}

// The liver through decimation with contraction (DECIMATE_CONTRACT_VOXELS=1.5): before the improver kept the outer
// boundary from crossing itself, one node slid through a cleft 0.2 mm wide, and tm-refine's rebuild crashed TetGen
// (SIGSEGV) on those faces in every try, so refinement stopped at round 0. Measured 2026-12-07: one edit refused,
// then 3 rounds. About 25 s on 2 idle cores.
TEST(WorkflowCliLong, LiverWithContractedSurfacesRefinesEveryRound)
{
    TempDir dir;
    const fs::path out = dir / "out";
    ASSERT_NO_FATAL_FAILURE(make_workflow(
        {"IMAGE=" + testing::data_path("samples/liver.inr.gz").string(), "DECIMATE_CONTRACT_VOXELS=1.5"}, out));
    EXPECT_EQ(testing::read_json(out / "check-mesh.json")["ok"], true);
    const auto refine = testing::read_json(out / "refine.json");
    EXPECT_EQ(refine["stop_reason"], "iteration cap");
    EXPECT_EQ(refine["iterations"].size(), 4u) << "round 0 and three rounds";
}

// The usc19-5 head resampled by tm-prep to 0.7 mm voxels (nearest neighbour), as a head segmented finer than the
// atlas would come: 22.6 M voxels, 2.6 M tets. Measured 2026-12-07: 10.28 degrees after tm-tetra (10.12 without the
// improver's last-round widening of the face bound), 10.79 after tm-refine. The same head resampled outside tm-prep
// kept tets of 9.14 (0.85 mm) and 8.92 degrees (0.7 mm) before this session's changes to the improver's last round
// (docs/volume.md). About 5-7 min on 2 cores.
TEST(WorkflowCliLong, HeadAtFinerVoxelsMeshesWithEveryTetAtTenDegreesOrMore)
{
    expect_real_volume_meshed_well("samples/usc19-5_head.nii.gz", "samples/usc19-5_head.json",
                                   {"PREP_ARGS=--spacing-mm 0.7 --nearest --fill-holes-under 8 --crop-pad 2"});
}

} // namespace
} // namespace tissuemesh

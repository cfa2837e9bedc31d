// The catalogue of bad inputs, through the programs a user runs: each case is one defect, and the program
// must exit with the documented code (2 bad input, 1 a checker found the input unfit), say what is wrong in
// one line that names the file, and leave no output behind. None may crash or hang (ctest's timeout).
#include <gtest/gtest.h>

#include <cctype>
#include <sstream>
#include <string>
#include <vector>

#include "tests/bad_input_cli/bad_input_files.h"
#include "tests/support/cli.h"

namespace tissuemesh::testing {
namespace {

struct BadCase {
    std::string name;                 ///< test name
    std::string tool;                 ///< tm-<verb>
    std::vector<std::string> args;    ///< "@x" stands for the file x in the case folder
    int exit_code;                    ///< 2: bad input or usage; 1: a checker found defects; 0: accepted
    std::vector<std::string> message; ///< parts the report must contain (stderr, or stdout for checkers)
    std::string output = "out";       ///< a file the program must not leave behind on failure ("" none)
};

std::ostream& operator<<(std::ostream& out, const BadCase& c) { return out << c.name; }

std::vector<std::string> expand(const std::vector<std::string>& args, const TempDir& dir)
{
    std::vector<std::string> result;
    for (const std::string& arg : args) result.push_back(arg.starts_with('@') ? (dir / arg.substr(1)).string() : arg);
    return result;
}

class BadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInput, ExitsWithTheCodeAndOneLineAndLeavesNothing)
{
    const BadCase& c = GetParam();
    TempDir dir;
    write_bad_input_files(dir.path());
    const CliResult result = run_cli(c.tool, expand(c.args, dir));
    ASSERT_EQ(result.exit_code, c.exit_code) << result.err << result.out;
    const std::string report = result.err + result.out;
    for (const std::string& part : c.message) EXPECT_NE(report.find(part), std::string::npos) << report;
    if (c.exit_code == 2) {
        // One line: "tm-x: error: <file>: <problem>; <what to do>".
        std::istringstream lines(result.err);
        std::size_t error_lines = 0;
        for (std::string line; std::getline(lines, line);) error_lines += line.find("error:") != std::string::npos;
        EXPECT_EQ(error_lines, 1u) << result.err;
    }
    if (c.exit_code != 0 && !c.output.empty()) {
        for (const std::string& name : dir.files()) EXPECT_FALSE(name.starts_with(c.output)) << name << " left behind";
    }
}

/// tm-solve on ok.msh with `args` added (a dipole, or electrodes, plus the file under test).
BadCase solve_case(std::string name, std::vector<std::string> args, std::vector<std::string> message)
{
    std::vector<std::string> all{"-i", "@ok.msh", "-o", "@out.vtu"};
    all.insert(all.end(), args.begin(), args.end());
    return {std::move(name), "tm-solve", all, 2, std::move(message)};
}

const std::vector<std::string> dipole{"--dipole", "5,5,5,0,0,1e-8"};

std::vector<std::string> with_dipole(std::vector<std::string> args)
{
    args.insert(args.begin(), dipole.begin(), dipole.end());
    return args;
}

// Images: readers of every format, and tissue contents that a step cannot use.
const std::vector<BadCase> image_cases{
    {"NiftiComplexVoxels", "tm-extract", {"-i", "@complex.nii", "-o", "@out.ply"}, 2, {"complex.nii", "datatype"}},
    {"NiftiInfiniteSpacing", "tm-extract", {"-i", "@inf.nii", "-o", "@out.ply"}, 2, {"inf.nii", "spacing along axis 2"}},
    {"NrrdWrongMagic", "tm-info", {"-i", "@magic.nrrd"}, 2, {"magic.nrrd"}},
    {"NrrdTruncated", "tm-extract", {"-i", "@short.nrrd", "-o", "@out.ply"}, 2, {"short.nrrd"}},
    {"MetaImageMissingData", "tm-info", {"-i", "@nofile.mhd"}, 2, {"nofile.mhd"}},
    {"MetaImageTruncated", "tm-extract", {"-i", "@short.mha", "-o", "@out.ply"}, 2, {"short.mha"}},
    {"OnlyBackground", "tm-extract", {"-i", "@one-label.nii", "-o", "@out.ply"}, 2, {"one-label.nii", "background"}},
    {"UnknownTissueToKeep", "tm-extract", {"-i", "@ok.nii", "-o", "@out.ply", "--tissues", "9"}, 2, {"9"}},
    {"PriorityOfAbsentTissue", "tm-extract", {"-i", "@ok.nii", "-o", "@out.ply", "--priority", "9=1"}, 2, {"9"}},
    {"BrokenNameTable",
     "tm-extract",
     {"-i", "@ok.nii", "-o", "@out.ply", "--labels", "@names-broken.json"},
     2,
     {"names-broken.json"}},
    {"OutputInMissingFolder", "tm-extract", {"-i", "@ok.nii", "-o", "@missing/out.ply"}, 2, {"missing"}},
    {"OutputIsAFolder", "tm-extract", {"-i", "@ok.nii", "-o", "@"}, 2, {}, ""},
    {"UnknownOutputFormat", "tm-extract", {"-i", "@ok.nii", "-o", "@out.xyz"}, 2, {".xyz"}},
    {"UnknownPhantom", "tm-phantom", {"sphere9", "-o", "@out.nii.gz"}, 2, {"sphere9", "spheres4"}},
    {"PhantomVoxelZero", "tm-phantom", {"spheres4", "--voxel-mm", "0", "-o", "@out.nii.gz"}, 2, {"0"}},
    {"PrepNegativeIslandSize", "tm-prep", {"-i", "@ok.nii", "-o", "@out.nii", "--remove-islands", "-3"}, 2, {"-3"}},
    {"PrepNegativePad", "tm-prep", {"-i", "@ok.nii", "-o", "@out.nii", "--crop-pad", "-1"}, 2, {"-1"}},
    {"PrepZeroHoleSize",
     "tm-prep",
     {"-i", "@ok.nii", "-o", "@out.nii", "--fill-holes-under", "0"},
     2,
     {"--fill-holes-under", "not in range 1"}},
    {"SmoothNegativeIterations",
     "tm-smooth",
     {"-i", "@ok.ply", "--image", "@ok.nii", "-o", "@out.ply", "--iterations", "-2"},
     2,
     {"-2"}},
    {"RefineNegativeNodeBudget", "tm-refine", {"--image", "@ok.nii", "-o", "@out.msh", "--max-nodes", "-1"}, 2, {"-1"}},
    {"DecimateNegativeTarget",
     "tm-decimate",
     {"-i", "@ok.ply", "-o", "@out.ply", "--target-triangles", "-5"},
     2,
     {"-5"}},
    {"ExtractBackgroundOutOfRange",
     "tm-extract",
     {"-i", "@ok.nii", "-o", "@out.ply", "--background", "70000"},
     2,
     {"70000"}},
};

// Images that are odd but valid: the step works and says what is unusual.
const std::vector<BadCase> odd_image_cases{
    {"OneVoxelImageGivesAClosedCube", "tm-extract", {"-i", "@one-voxel.nii", "-o", "@cube.ply", "-q"}, 0, {}},
    {"TissueOnTheBorderIsReported", "tm-info", {"-i", "@border.nii"}, 0, {"border"}},
};

// Surfaces: readers, then the checker (exit 1 with the defect) and the mesher (exit 2, nothing written).
const std::vector<BadCase> surface_cases{
    {"PlyEmpty", "tm-check-surface", {"@empty.ply"}, 2, {"empty.ply"}},
    {"PlyWrongMagic", "tm-check-surface", {"@magic.ply"}, 2, {"magic.ply", "not a PLY file"}},
    {"PlyTruncated", "tm-check-surface", {"@truncated.ply"}, 2, {"truncated.ply", "truncated"}},
    {"PlyDanglingIndex",
     "tm-tetra",
     {"-i", "@dangling.ply", "-o", "@out.msh"},
     2,
     {"dangling.ply", "refers to vertex 7"}},
    {"PlyNanCoordinate", "tm-tetra", {"-i", "@nan.ply", "-o", "@out.msh"}, 2, {"nan.ply"}},
    {"OffCountsExceedData", "tm-check-surface", {"@counts.off"}, 2, {"counts.off"}},
    {"StlTruncated", "tm-check-surface", {"@truncated.stl"}, 2, {"truncated.stl"}},
    {"HoleIsReported", "tm-check-surface", {"@hole.ply"}, 1, {"brain"}},
    {"HoleStopsTheMesher", "tm-tetra", {"-i", "@hole.ply", "-o", "@out.msh"}, 2, {"hole.ply"}},
    {"FlippedTriangleIsReported", "tm-check-surface", {"@flipped.ply"}, 1, {"brain"}},
    {"DuplicateTriangleIsReported", "tm-check-surface", {"@duplicate.ply"}, 1, {"duplicate"}},
    {"TwinVerticesAreReported", "tm-check-surface", {"@twin-vertices.ply"}, 1, {"brain"}},
    {"CrossingTissuesAreReported", "tm-check-surface", {"@crossing.ply"}, 1, {"skull"}},
    {"CrossingTissuesStopTheMesher", "tm-tetra", {"-i", "@crossing.ply", "-o", "@out.msh"}, 2, {"skull", "brain"}},
    {"SmoothNeedsAFitInput", "tm-smooth", {"-i", "@hole.ply", "--image", "@ok.nii", "-o", "@out.ply"}, 2, {"hole.ply"}},
    {"DecimateNeedsAFitInput", "tm-decimate", {"-i", "@crossing.ply", "-o", "@out.ply"}, 2, {"crossing.ply"}},
    {"RemeshNeedsAFitInput", "tm-remesh", {"-i", "@flipped.ply", "-o", "@out.ply"}, 2, {"flipped.ply"}},
    {"TetraNegativeVolume", "tm-tetra", {"-i", "@ok.ply", "-o", "@out.msh", "--max-volume", "-1"}, 2, {"-1"}},
    {"TetraUnknownTissueSize", "tm-tetra", {"-i", "@ok.ply", "-o", "@out.msh", "--max-volume", "liver=2"}, 2, {"liver"}},
};

// Tet meshes and the solver's tables.
const std::vector<BadCase> mesh_cases{
    {"MshFlatTetIsReported", "tm-check-mesh", {"@flat.msh"}, 1, {"volume 0 mm^3", "NOT fit for FEM"}},
    {"MshDanglingNode", "tm-check-mesh", {"@dangling.msh"}, 2, {"dangling.msh"}},
    {"MshNanCoordinate", "tm-solve", {"-i", "@nan.msh", "-o", "@out.vtu", "--dipole", "5,5,5,0,0,1e-8"}, 2, {"nan.msh"}},
    {"MshTruncated",
     "tm-assess",
     {"-i", "@truncated.msh", "--image", "@ok.nii", "-o", "@out.vtu"},
     2,
     {"truncated.msh"}},
    {"MshWithoutTets",
     "tm-solve",
     {"-i", "@no-tets.msh", "-o", "@out.vtu", "--dipole", "5,5,5,0,0,1e-8"},
     2,
     {"no-tets.msh", "no tetrahedra"}},
    {"MeditTruncated", "tm-check-mesh", {"@bad.mesh"}, 2, {"bad.mesh"}},
    {"VtuOtherCellType",
     "tm-convert",
     {"-i", "@triangle.vtu", "-o", "@out.msh"},
     2,
     {"triangle.vtu", "triangle (VTK type 5)", "only tetrahedra"}},
    {"VtuDanglingIndex", "tm-check-mesh", {"@dangling.vtu"}, 2, {"dangling.vtu", "refers to point 9"}},
    {"VtuTruncated",
     "tm-solve",
     {"-i", "@truncated.vtu", "-o", "@out.vtu", "--dipole", "5,5,5,0,0,1e-8"},
     2,
     {"truncated.vtu", "truncated"}},
    {"VtuFieldViewWithoutTheArray",
     "tm-render",
     {"--view", "field", "-i", "@ok.vtu", "-o", "@out.png"},
     2,
     {"ok.vtu", "no point or cell array \"potential_V\"", "tm-solve"}},
    solve_case("ConductivityUnknownName", with_dipole({"--conductivity", "@cond-unknown.json"}), {"liver"}),
    solve_case("ConductivityUnknownLabel", with_dipole({"--conductivity", "@cond-label.json"}), {"7"}),
    solve_case("ConductivityNegative", with_dipole({"--conductivity", "@cond-negative.json"}),
               {"cond-negative.json", "positive"}),
    solve_case("ConductivityNotANumber", with_dipole({"--conductivity", "@cond-text.json"}), {"cond-text.json"}),
    solve_case("ConductivityBrokenJson", with_dipole({"--conductivity", "@cond-broken.json"}), {"cond-broken.json"}),
    solve_case("ConductivityTensorOfThree", with_dipole({"--conductivity", "@cond-tensor.json"}), {"cond-tensor.json"}),
    solve_case("ElectrodeOffTheScalp", {"--electrode", "100,100,100,2,1e-3", "--electrode", "0,0,0,2,-1e-3"}, {"100"}),
    solve_case("ElectrodeNegativeRadius", {"--electrode", "0,0,0,-2,1e-3", "--electrode", "20,0,0,2,-1e-3"}, {"-2"}),
    solve_case("DipoleNotFinite", {"--dipole", "5,5,nan,0,0,1e-8"}, {"nan"}),
    solve_case("NoSource", {}, {"no source"}),
    solve_case("SensorsWrongHeader",
               with_dipole({"--sensors", "@sensors-header.csv", "--sensor-potentials", "@out.csv"}),
               {"sensors-header.csv"}),
    solve_case("SensorsNotANumber",
               with_dipole({"--sensors", "@sensors-number.csv", "--sensor-potentials", "@out.csv"}),
               {"sensors-number.csv"}),
    {"RefineUnknownPlacement",
     "tm-refine",
     {"-i", "@ok.msh", "--image", "@ok.nii", "-o", "@out.msh", "--placement", "random"},
     2,
     {"random"}},
    {"AssessOutputInMissingFolder",
     "tm-assess",
     {"-i", "@ok.msh", "--image", "@ok.nii", "-o", "@missing/out.vtu"},
     2,
     {"missing"}},
};

// tm-solve's own files: conductivity tables, electrode montages (--electrodes) and sensors.
const std::vector<BadCase> solver_file_cases{
    solve_case("ConductivityEmptyFile", with_dipole({"--conductivity", "@cond-empty.json"}),
               {"cond-empty.json: the file is empty"}),
    solve_case("ConductivityTissueTwice", with_dipole({"--conductivity", "@cond-twice.json"}),
               {"cond-twice.json: \"brain\" and \"BRAIN\" name the same tissue"}),
    solve_case("ConductivityNameAndLabelOfOneTissue", with_dipole({"--conductivity", "@cond-name-and-label.json"}),
               {"cond-name-and-label.json", "'1' and 'brain' both name tissue 1 (brain)"}),
    solve_case("ConductivityNestedTooDeep", with_dipole({"--conductivity", "@cond-deep.json"}),
               {"cond-deep.json line 1: nested 4 deep"}),
    solve_case("ConductivityNumberOverflows", with_dipole({"--conductivity", "@cond-overflow.json"}),
               {"cond-overflow.json: not valid JSON", "1e999"}),
    solve_case("MontageEmptyFile", {"--electrodes", "@montage-empty.csv"}, {"montage-empty.csv: the file is empty"}),
    solve_case("MontageHeaderOnly", {"--electrodes", "@montage-header-only.csv"},
               {"montage-header-only.csv: no electrodes"}),
    solve_case("MontageCurrentInMilliampere", {"--electrodes", "@montage-ma.csv"},
               {"montage-ma.csv line 1: unknown column 'current_ma'", "current_a"}),
    solve_case("MontageNegativeRadius", {"--electrodes", "@montage-negative.csv"},
               {"montage-negative.csv line 2: radius_mm is -10"}),
    solve_case("MontageNotANumber", {"--electrodes", "@montage-nan.csv"},
               {"montage-nan.csv line 3, column current_a: 'nan'"}),
    solve_case("MontageTruncatedRow", {"--electrodes", "@montage-cut.csv"}, {"montage-cut.csv line 3: 3 fields"}),
    solve_case("MontageNameTwice", {"--electrodes", "@montage-twice.csv"},
               {"montage-twice.csv line 3: name 'Cz' is also on line 2"}),
    solve_case("MontageElectrodeOffTheScalp", {"--electrodes", "@montage-off.csv"},
               {"Oz (", "montage-off.csv line 3) at (100, 100, 100) mm"}),
    solve_case("MontageCurrentsDoNotSumToZero", {"--electrodes", "@montage-unbalanced.csv"},
               {"electrode currents sum to"}),
    solve_case("MontageWithoutRowsEvenWithAFlag",
               {"--electrodes", "@montage-header-only.csv", "--electrode", "0,0,0,30,1e-3"},
               {"montage-header-only.csv: no electrodes"}),
    solve_case("SensorsEmptyFile", with_dipole({"--sensors", "@sensors-empty.csv", "--sensor-potentials", "@out.csv"}),
               {"sensors-empty.csv: the file is empty"}),
    solve_case("SensorsInfinite", with_dipole({"--sensors", "@sensors-nan.csv", "--sensor-potentials", "@out.csv"}),
               {"sensors-nan.csv line 3, column y: 'inf'"}),
    solve_case("SensorsWithoutZ", with_dipole({"--sensors", "@sensors-no-z.csv", "--sensor-potentials", "@out.csv"}),
               {"sensors-no-z.csv line 1: the header has no column 'z'"}),
    solve_case("SensorsNameTwice", with_dipole({"--sensors", "@sensors-twice.csv", "--sensor-potentials", "@out.csv"}),
               {"sensors-twice.csv line 3: name 'Cz' is also on line 2"}),
};

// Every program refuses a --json summary it could not write before it starts: found in review, tm-info
// printed the error and exited 0; then the summary was refused after the outputs were written. Each case
// is an otherwise working command.
BadCase summary_case(const std::string& tool, std::vector<std::string> args)
{
    args.insert(args.end(), {"--json", "@no/such/x.json"});
    std::string name = "JsonSummaryInAMissingFolder"; // + the verb in CamelCase: tm-check-mesh -> CheckMesh
    bool word_start = true;
    for (const char c : tool.substr(3)) {
        if (c != '-') name += word_start ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
        word_start = c == '-';
    }
    return {name, tool, args, 2, {"--json", "x.json", "no/such does not exist"}};
}

const std::vector<BadCase> summary_cases{
    summary_case("tm-info", {"-i", "@ok.nii"}),
    summary_case("tm-phantom", {"spheres4", "--voxel-mm", "4", "-o", "@out.nii.gz"}),
    summary_case("tm-prep", {"-i", "@ok.nii", "-o", "@out.nii"}),
    summary_case("tm-extract", {"-i", "@ok.nii", "-o", "@out.ply"}),
    summary_case("tm-snake", {"-i", "@ok.nii", "--tissue", "1", "-o", "@out.ply"}),
    summary_case("tm-smooth", {"-i", "@ok.ply", "--image", "@ok.nii", "-o", "@out.ply"}),
    summary_case("tm-decimate", {"-i", "@ok.ply", "-o", "@out.ply"}),
    summary_case("tm-remesh", {"-i", "@ok.ply", "-o", "@out.ply"}),
    summary_case("tm-repair", {"-i", "@ok.ply", "-o", "@out.ply"}),
    summary_case("tm-check-surface", {"-i", "@ok.ply"}),
    summary_case("tm-tetra", {"-i", "@ok.ply", "-o", "@out.msh"}),
    summary_case("tm-improve", {"-i", "@ok.msh", "-o", "@out.msh"}),
    summary_case("tm-check-mesh", {"@ok.msh"}),
    summary_case("tm-assess", {"-i", "@ok.msh", "--image", "@ok.nii", "-o", "@out.vtu"}),
    summary_case("tm-refine", {"--image", "@ok.nii", "-o", "@out.msh"}),
    summary_case("tm-convert", {"-i", "@ok.msh", "-o", "@out.vtu"}),
    summary_case("tm-solve", {"-i", "@ok.msh", "-o", "@out.vtu", "--dipole", "5,5,5,0,0,1e-8"}),
    summary_case("tm-leadfield",
                 {"-i", "@ok.msh", "--sensors", "@sensors.csv", "--sources", "@sources.csv", "-o", "@out.npy"}),
    summary_case("tm-render", {"--view", "quality", "-i", "@ok.msh", "-o", "@out.png"}),
    summary_case("tm-report", {"-i", "@", "-o", "@out.html"}),
};

std::string case_name(const ::testing::TestParamInfo<BadCase>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Images, BadInput, ::testing::ValuesIn(image_cases), case_name);
INSTANTIATE_TEST_SUITE_P(OddImages, BadInput, ::testing::ValuesIn(odd_image_cases), case_name);
INSTANTIATE_TEST_SUITE_P(Surfaces, BadInput, ::testing::ValuesIn(surface_cases), case_name);
INSTANTIATE_TEST_SUITE_P(Meshes, BadInput, ::testing::ValuesIn(mesh_cases), case_name);
INSTANTIATE_TEST_SUITE_P(SolverFiles, BadInput, ::testing::ValuesIn(solver_file_cases), case_name);
INSTANTIATE_TEST_SUITE_P(Summaries, BadInput, ::testing::ValuesIn(summary_cases), case_name);

} // namespace
} // namespace tissuemesh::testing

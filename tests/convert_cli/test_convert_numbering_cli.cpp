// tm-convert --tissue-numbering simnibs | duneuro as a user runs it: a tissue SimNIBS has no number for fails with
// one line naming it until a table maps it; DUNEuro gets its conductivity file; flags that do not fit together are
// refused before anything is read; failures leave nothing behind. (The files themselves, read back by meshio,
// gmsh and a dune-grid-rule parser: tests/io_clients/test_simnibs_duneuro.cpp.)
#include <algorithm>
#include <fstream>
#include <gtest/gtest.h>

#include "core/atomic_file.h"
#include "io/tet_mesh_io.h"
#include "tests/support/cli.h"
#include "tests/support/programs.h"

namespace tissuemesh {
namespace {

using testing::run_cli;

/// The nested cubes named as usc19-5 names two of its tissues: scalp outside, air cavities inside.
std::filesystem::path write_head(const testing::TempDir& dir)
{
    TetMesh mesh = testing::nested_cubes_mesh();
    mesh.names = {{1, "Scalp"}, {2, "air cavities"}};
    io::write_tet_mesh(mesh, dir / "head.msh");
    return dir / "head.msh";
}

void expect_refused(const testing::CliResult& result, const std::string& part)
{
    EXPECT_EQ(result.exit_code, 2) << result.err;
    EXPECT_NE(result.err.find(part), std::string::npos) << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
}

TEST(ConvertNumberingCli, SimnibsNamesTheTissuesWithoutATagUntilATableMapsThem)
{
    testing::TempDir dir;
    const std::string head = write_head(dir).string(), out = (dir / "simnibs.msh").string();
    expect_refused(run_cli("tm-convert", {"-i", head, "-o", out, "--tissue-numbering", "simnibs"}),
                   "\"air cavities\" (label 2)");
    EXPECT_FALSE(std::filesystem::exists(out));
    std::ofstream(dir / "tags.json") << "{\"Air Cavities\": 13}";
    const auto done = run_cli("tm-convert", {"-i", head, "-o", out, "--tissue-numbering", "simnibs", "--tissue-tags",
                                             (dir / "tags.json").string()});
    ASSERT_EQ(done.exit_code, 0) << done.err;
    const TetMesh back = io::read_tet_mesh(out);
    const std::set<Label> tags(back.tet_labels.begin(), back.tet_labels.end());
    EXPECT_EQ(tags, (std::set<Label>{5, 13}));
    std::set<Label> face_tags;
    for (const LabelPair& pair : back.face_sides) face_tags.insert(pair.from);
    EXPECT_EQ(face_tags, (std::set<Label>{5}))
        << "the outside 1005, the air's surface against scalp 1005 (scalp ranks before 13)";
}

TEST(ConvertNumberingCli, DuneuroWritesItsConductivityFileBeside)
{
    testing::TempDir dir;
    const std::string head = write_head(dir).string(), out = (dir / "duneuro.msh").string();
    // The head defaults know the scalp, not the air cavities.
    expect_refused(run_cli("tm-convert", {"-i", head, "-o", out, "--tissue-numbering", "duneuro"}), "air cavities");
    EXPECT_FALSE(std::filesystem::exists(out));
    EXPECT_FALSE(std::filesystem::exists(dir / "duneuro.con"));
    std::ofstream(dir / "cond.json") << "{\"air cavities\": 1e-6}";
    const auto done = run_cli("tm-convert", {"-i", head, "-o", out, "--tissue-numbering", "duneuro", "--conductivity",
                                             (dir / "cond.json").string()});
    ASSERT_EQ(done.exit_code, 0) << done.err;
    std::ifstream con(dir / "duneuro.con");
    std::vector<double> values;
    for (double value; con >> value;) values.push_back(value);
    EXPECT_EQ(values, (std::vector<double>{0.43, 1e-6})) << "scalp (label 1, tag 1), air cavities (label 2, tag 2)";
    const TetMesh back = io::read_tet_mesh(out);
    EXPECT_TRUE(back.faces.empty()) << "tets only";
    EXPECT_EQ(back.names, (TissueNames{{1, "Scalp"}, {2, "air_cavities"}}));
}

TEST(ConvertNumberingCli, FlagsThatDoNotFitAreRefusedBeforeReading)
{
    testing::TempDir dir;
    std::ofstream(dir / "t.json") << "{}";
    const std::string missing = (dir / "missing.msh").string(), out = (dir / "o.msh").string();
    expect_refused(run_cli("tm-convert", {"-i", missing, "-o", out, "--tissue-tags", (dir / "t.json").string()}),
                   "--tissue-numbering simnibs");
    expect_refused(run_cli("tm-convert", {"-i", missing, "-o", out, "--tissue-numbering", "duneuro", "--binary"}),
                   "drop --binary");
    expect_refused(
        run_cli("tm-convert", {"-i", missing, "-o", out, "--tissue-numbering", "simnibs", "--msh-version", "4.1"}),
        "drop --msh-version 4.1");
    const std::string head = write_head(dir).string();
    expect_refused(run_cli("tm-convert", {"-i", head, "-o", (dir / "o.vtu").string(), "--tissue-numbering", "simnibs"}),
                   "write a .msh");
    EXPECT_EQ(dir.files(), (std::vector<std::string>{"head.msh", "t.json"}));
}

} // namespace
} // namespace tissuemesh

// tm-convert as a user runs it: any tet mesh format to any other, surfaces likewise, counts in --json,
// failures with exit 2, one line naming the problem, and nothing left behind.
#include <algorithm>
#include <gtest/gtest.h>

#include "io/surface_io.h"
#include "io/tet_mesh_io.h"
#include "tests/support/cli.h"
#include "tests/support/complexes.h"
#include "tests/support/programs.h"

namespace tissuemesh {
namespace {

using testing::run_cli;

TEST(ConvertCli, TetMeshesThroughEveryFormatKeepCountsAndVolumes)
{
    testing::TempDir dir;
    const TetMesh mesh = testing::nested_cubes_mesh();
    io::write_tet_mesh(mesh, dir / "start.msh");
    // A chain through every readable variant: each step reads the previous step's output.
    const std::vector<std::vector<std::string>> steps{{"a.msh", "--msh-version", "4.1", "--binary"},
                                                      {"b.mesh"},
                                                      {"c.node"},
                                                      {"d.msh", "--binary"},
                                                      {"e.msh", "--msh-version", "4.1"},
                                                      {"f.inp"}};
    std::string previous = "start.msh";
    for (const auto& step : steps) {
        SCOPED_TRACE(previous + " -> " + step[0]);
        std::vector<std::string> args{"-i",     (dir / previous).string(), "-o", (dir / step[0]).string(),
                                      "--json", (dir / "s.json").string(), "-q"};
        args.insert(args.end(), step.begin() + 1, step.end());
        const auto result = run_cli("tm-convert", args);
        ASSERT_EQ(result.exit_code, 0) << result.err;
        const auto summary = testing::read_json(dir / "s.json");
        EXPECT_EQ(summary.at("tets").get<std::size_t>(), mesh.tets.size());
        EXPECT_EQ(summary.at("nodes").get<std::size_t>(), mesh.vertices.size());
        EXPECT_EQ(summary.at("tissues").get<int>(), 2);
        const TetMesh back = io::read_tet_mesh(dir / step[0]);
        const auto volumes = testing::tissue_volumes(back);
        EXPECT_NEAR(volumes.at(1), 56.0, 1e-9);
        EXPECT_NEAR(volumes.at(2), 8.0, 1e-9);
        if (step[0] != "f.inp") {
            EXPECT_EQ(back.faces.size(), mesh.faces.size());
        }
        previous = step[0];
    }
    const auto vtu = run_cli("tm-convert", {"-i", (dir / "f.inp").string(), "-o", (dir / "g.vtu").string(), "-q"});
    EXPECT_EQ(vtu.exit_code, 0) << vtu.err;
}

TEST(ConvertCli, SurfacesAndTheFacesOfAMesh)
{
    testing::TempDir dir;
    InterfaceComplex complex;
    testing::add_box(complex, {0, 0, 0}, {2, 2, 2}, 1, 0);
    io::write_surface(complex, dir / "box.ply");
    for (const char* name : {"a.obj", "b.off", "c.stl", "d.vtp", "e.ply"}) {
        const auto result = run_cli("tm-convert", {"-i", (dir / "box.ply").string(), "-o", (dir / name).string(),
                                                   "--json", (dir / "s.json").string(), "-q"});
        ASSERT_EQ(result.exit_code, 0) << name << ": " << result.err;
        EXPECT_EQ(testing::read_json(dir / "s.json").at("triangles").get<std::size_t>(), 12u) << name;
        EXPECT_EQ(io::read_surface(dir / name).triangles.size(), 12u) << name;
    }
    io::write_tet_mesh(testing::nested_cubes_mesh(), dir / "m.msh");
    const auto faces =
        run_cli("tm-convert", {"-i", (dir / "m.msh").string(), "-o", (dir / "faces.ply").string(), "-q"});
    ASSERT_EQ(faces.exit_code, 0) << faces.err;
    const InterfaceComplex interfaces = io::read_surface(dir / "faces.ply");
    EXPECT_EQ(interfaces.triangles.size(), testing::nested_cubes_mesh().faces.size());
}

TEST(ConvertCli, FailuresExitTwoWithOneLineAndLeaveNothing)
{
    testing::TempDir dir;
    InterfaceComplex complex;
    testing::add_box(complex, {0, 0, 0}, {2, 2, 2}, 1, 0);
    io::write_surface(complex, dir / "box.ply");
    io::write_tet_mesh(testing::nested_cubes_mesh(), dir / "m.msh");
    const std::string box = (dir / "box.ply").string(), mesh = (dir / "m.msh").string();
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
        {{"-i", box, "-o", (dir / "x.msh").string()}, "tetrahedralize it with tm-tetra"},
        {{"-i", mesh, "-o", (dir / "x.msh").string(), "--msh-version", "3"}, "--msh-version"},
        {{"-i", (dir / "missing.msh").string(), "-o", (dir / "x.mesh").string()}, "missing.msh"},
        {{"-i", mesh, "-o", (dir / "x.xyz").string()}, "x.xyz"},
        {{"-i", (dir / "m.vtu").string(), "-o", (dir / "x.msh").string()}, "m.vtu"}};
    for (const auto& [args, expected] : cases) {
        const auto result = run_cli("tm-convert", args);
        EXPECT_EQ(result.exit_code, 2) << result.err;
        EXPECT_NE(result.err.find(expected), std::string::npos) << result.err;
        EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    }
    EXPECT_EQ(dir.files(), (std::vector<std::string>{"box.ply", "m.msh"})) << "nothing half-written";
}

} // namespace
} // namespace tissuemesh

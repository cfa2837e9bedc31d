// tm-convert with .vtu input: to .msh (the mesh), and to .vtu keeping every array (tm-solve's fields), ASCII
// or compressed.
#include <gtest/gtest.h>

#include "io/read_vtu.h"
#include "io/tet_mesh_io.h"
#include "tests/support/cli.h"
#include "tests/support/programs.h"

namespace tissuemesh {
namespace {

TEST(ConvertVtuCli, VtuToVtuKeepsTheArraysAndVtuToMshTheMesh)
{
    testing::TempDir dir;
    const TetMesh mesh = testing::nested_cubes_mesh();
    std::vector<double> phi, e;
    for (const Vec3& p : mesh.vertices) phi.push_back(p[0] * 1e-3);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) e.push_back(static_cast<double>(t) / 7);
    io::write_vtu(mesh, dir / "solution.vtu", {io::make_vtu_array("potential_V", phi)},
                  {io::make_vtu_array("E_magnitude_V_per_m", e)});
    for (const bool ascii : {false, true}) {
        std::vector<std::string> args{"-i",     (dir / "solution.vtu").string(), "-o", (dir / "copy.vtu").string(),
                                      "--json", (dir / "copy.json").string()};
        if (ascii) args.push_back("--vtu-ascii");
        const auto result = testing::run_cli("tm-convert", args);
        ASSERT_EQ(result.exit_code, 0) << result.err;
        const io::VtuContent copy = io::read_vtu(dir / "copy.vtu");
        EXPECT_EQ(copy.mesh.tets, mesh.tets);
        EXPECT_EQ(copy.mesh.tet_labels, mesh.tet_labels);
        ASSERT_NE(copy.point_array("potential_V"), nullptr);
        EXPECT_EQ(copy.point_array("potential_V")->values, phi) << "17 digits or raw doubles: exact";
        ASSERT_NE(copy.cell_array("E_magnitude_V_per_m"), nullptr);
        EXPECT_EQ(copy.cell_array("E_magnitude_V_per_m")->values, e);
        EXPECT_EQ(testing::read_json(dir / "copy.json")["arrays"], 2);
    }
    const auto result = testing::run_cli(
        "tm-convert", {"-i", (dir / "solution.vtu").string(), "-o", (dir / "mesh.msh").string(), "-q"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(testing::tissue_volumes(io::read_tet_mesh(dir / "mesh.msh")), testing::tissue_volumes(mesh));
}

} // namespace
} // namespace tissuemesh

// tm-improve as a user runs it on a mesh of tm-tetra --no-improve, and tm-check-mesh --surface on the result.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

using testing::read_json;
using testing::run_cli;
using testing::TempDir;

TEST(ImproveCli, RaisesTheSmallestAngleAndKeepsTheInterfacesOnTheSurface)
{
    TempDir dir;
    const auto image = (dir / "junction.nii.gz").string(), surface = (dir / "surface.ply").string();
    ASSERT_EQ(run_cli("tm-phantom", {"junction", "--voxel-mm", "2", "-o", image, "-q"}).exit_code, 0);
    ASSERT_EQ(run_cli("tm-extract", {"-i", image, "-o", surface, "-q"}).exit_code, 0);
    const auto raw = (dir / "raw.msh").string(), better = (dir / "better.msh").string();
    const auto tetra = run_cli("tm-tetra", {"-i", surface, "-o", raw, "--no-improve", "-q"});
    ASSERT_EQ(tetra.exit_code, 0) << tetra.err;
    const auto improve = run_cli(
        "tm-improve", {"-i", raw, "-o", better, "--surface", surface, "--json", (dir / "improve.json").string(), "-q"});
    ASSERT_EQ(improve.exit_code, 0) << improve.err;
    const nlohmann::json summary = read_json(dir / "improve.json");
    EXPECT_GT(summary["after"]["min_dihedral_deg"].get<double>(), summary["before"]["min_dihedral_deg"].get<double>());
    EXPECT_GT(summary["after"]["p1_min_dihedral_deg"].get<double>(),
              summary["before"]["p1_min_dihedral_deg"].get<double>());
    const auto check = run_cli("tm-check-mesh", {"-i", better, "--image", image, "--surface", surface, "--json",
                                                 (dir / "check.json").string(), "-q"});
    EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
    const nlohmann::json distance = read_json(dir / "check.json")["interface_distance"];
    EXPECT_LT(distance["max_node_mm"].get<double>(), 1e-9);
    EXPECT_LT(distance["max_face_voxels"].get<double>(), 0.1); // the bound
    EXPECT_EQ(distance["unmatched_faces"].get<std::size_t>(), 0u);
}

TEST(ImproveCli, AMissingMeshExitsTwoAndWritesNothing)
{
    TempDir dir;
    const auto result =
        run_cli("tm-improve", {"-i", (dir / "none.msh").string(), "-o", (dir / "out.msh").string(), "-q"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_FALSE(std::filesystem::exists(dir / "out.msh"));
}

} // namespace
} // namespace tissuemesh

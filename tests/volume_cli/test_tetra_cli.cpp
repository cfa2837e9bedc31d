// The surface-to-mesh steps as a user runs them: tm-phantom -> tm-extract -> tm-tetra -> tm-check-mesh.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/error.h"
#include "io/surface_io.h"
#include "io/tet_mesh_io.h"
#include "tests/support/cli.h"
#include "tests/support/complexes.h"

namespace tissuemesh {
namespace {

using testing::read_json;
using testing::run_cli;
using testing::TempDir;

/// Writes the named phantom at the given voxel size and its interface complex into `dir`.
void make_surface(const TempDir& dir, const std::string& phantom, const std::string& voxel_mm)
{
    const auto image = (dir / (phantom + ".nii.gz")).string();
    ASSERT_EQ(run_cli("tm-phantom", {phantom, "--voxel-mm", voxel_mm, "-o", image, "-q"}).exit_code, 0);
    const auto names = (dir / (phantom + ".labels.json")).string();
    const auto extracted =
        run_cli("tm-extract", {"-i", image, "--labels", names, "-o", (dir / "surface.ply").string(), "-q"});
    ASSERT_EQ(extracted.exit_code, 0) << extracted.err;
}

TEST(TetraCli, JunctionPhantomBecomesAConformingMeshMatchingTheVoxels)
{
    TempDir dir;
    make_surface(dir, "junction", "2");
    const auto tetra = run_cli("tm-tetra", {"-i", (dir / "surface.ply").string(), "-o", (dir / "mesh.msh").string(),
                                            "--json", (dir / "tetra.json").string(), "-q"});
    ASSERT_EQ(tetra.exit_code, 0) << tetra.err;
    const auto check =
        run_cli("tm-check-mesh", {(dir / "mesh.msh").string(), "--image", (dir / "junction.nii.gz").string(), "--json",
                                  (dir / "check.json").string(), "-q"});
    EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
    const nlohmann::json summary = read_json(dir / "check.json");
    EXPECT_TRUE(summary["ok"].get<bool>());
    // All three tissues survive, each one piece, and each matches its voxels: the tets' tissue comes from
    // interfaces built from those voxels, so only centres within half a voxel of an interface can differ.
    for (const char* label : {"1", "2", "3"}) {
        ASSERT_TRUE(summary["tissues"].contains(label)) << "tissue " << label << " lost";
        EXPECT_EQ(summary["tissues"][label]["components"].get<int>(), 1) << label;
        EXPECT_GE(summary["tissues"][label]["dice"].get<double>(), 0.97) << label;
    }
    // With -Y TetGen splits no interface triangle, so every one is a tet face; the improver may split some at
    // points of the surface, each split adding two faces (one per face on the edge it splits, beyond two).
    const InterfaceComplex surface = io::read_surface(dir / "surface.ply");
    const nlohmann::json report = read_json(dir / "tetra.json");
    EXPECT_EQ(report["split_interface_triangles"].get<std::size_t>(), 0u);
    const auto faces = report["interface_faces"].get<std::size_t>();
    const auto splits = report["improvement"]["nodes_inserted_on_interfaces"].get<std::size_t>();
    EXPECT_GE(faces, surface.triangles.size());
    EXPECT_LE(faces, surface.triangles.size() + 4 * splits);
}

TEST(TetraCli, KeepingTheVoxelSidesKeepsTheDiceOfTheUnimprovedMesh)
{
    // The `thin` phantom's one-voxel shell through decimation and remeshing, as the workflow makes its surfaces.
    TempDir dir;
    make_surface(dir, "thin", "2");
    const std::string surface = (dir / "remeshed.ply").string(), image = (dir / "thin.nii.gz").string();
    const std::string decimated = (dir / "decimated.ply").string();
    ASSERT_EQ(run_cli("tm-decimate", {"-i", (dir / "surface.ply").string(), "-o", decimated, "--max-distance-mm", "0.5",
                                      "--max-edge-mm", "8", "--max-normal-change-deg", "45", "-q"})
                  .exit_code,
              0);
    ASSERT_EQ(run_cli("tm-remesh",
                      {"-i", decimated, "-o", surface, "--edge-mm", "6", "--keep-voxel-sides", "--image", image, "-q"})
                  .exit_code,
              0);
    const auto mesh_and_check = [&](const std::string& name, std::vector<std::string> flags) {
        std::vector<std::string> args{
            "-i", surface, "-o", (dir / (name + ".msh")).string(), "--json", (dir / (name + ".json")).string(), "-q"};
        args.insert(args.end(), flags.begin(), flags.end());
        const auto tetra = run_cli("tm-tetra", args);
        EXPECT_EQ(tetra.exit_code, 0) << tetra.err;
        const auto check = run_cli("tm-check-mesh", {(dir / (name + ".msh")).string(), "--image", image, "--json",
                                                     (dir / (name + "-check.json")).string(), "-q"});
        EXPECT_EQ(check.exit_code, 0) << check.err;
        return read_json(dir / (name + "-check.json"));
    };
    const nlohmann::json meshed = mesh_and_check("meshed", {"--no-improve"});
    const nlohmann::json kept = mesh_and_check("kept", {"--improve-keep-voxel-sides", "--image", image});
    const nlohmann::json report = read_json(dir / "kept.json");
    EXPECT_GT(report["improvement"]["refused_by_voxels"].get<std::size_t>(), 0u);
    EXPECT_GT(kept["min_dihedral_deg"].get<double>(), meshed["min_dihedral_deg"].get<double>());
    for (const auto& [label, tissue] : meshed["tissues"].items())
        EXPECT_GE(kept["tissues"][label]["dice"].get<double>(), tissue["dice"].get<double>() - 1e-5) << label;
    // Refused, nothing written: the switch without an image, an image without the switch.
    const std::string out = (dir / "out.msh").string();
    const auto no_image = run_cli("tm-tetra", {"-i", surface, "-o", out, "--improve-keep-voxel-sides"});
    EXPECT_EQ(no_image.exit_code, 2);
    EXPECT_NE(no_image.err.find("give --image"), std::string::npos) << no_image.err;
    const auto idle_image = run_cli("tm-tetra", {"-i", surface, "-o", out, "--image", image});
    EXPECT_EQ(idle_image.exit_code, 2);
    EXPECT_NE(idle_image.err.find("only for --improve-keep-voxel-sides"), std::string::npos) << idle_image.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(TetraCli, EveryOutputFormatReadsBackWithItsTissues)
{
    TempDir dir;
    make_surface(dir, "thin", "4");
    for (const char* name : {"mesh.msh", "mesh.mesh", "mesh.vtu"})
        ASSERT_EQ(
            run_cli("tm-tetra", {"-i", (dir / "surface.ply").string(), "-o", (dir / name).string(), "-q"}).exit_code, 0)
            << name;
    const TetMesh msh = io::read_tet_mesh(dir / "mesh.msh");
    const TetMesh medit = io::read_tet_mesh(dir / "mesh.mesh");
    EXPECT_EQ(msh.tets.size(), medit.tets.size());
    EXPECT_EQ(msh.tet_labels, medit.tet_labels);
    EXPECT_EQ(msh.faces.size(), medit.faces.size());
    EXPECT_EQ(msh.names.at(1), "shell");
    std::ifstream vtu(dir / "mesh.vtu");
    const std::string text((std::istreambuf_iterator<char>(vtu)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("NumberOfCells=\"" + std::to_string(msh.tets.size()) + "\""), std::string::npos);
}

TEST(TetraCli, IntersectingSurfaceFailsWithTissuesAndPlaceAndLeavesNoMesh)
{
    // Two closed boxes of different tissues that pass through each other.
    InterfaceComplex complex;
    testing::add_box(complex, {0, 0, 0}, {10, 10, 10}, 1, 0);
    testing::add_box(complex, {5, 5, 5}, {15, 15, 15}, 2, 0);
    complex.names = {{0, "background"}, {1, "scalp"}, {2, "skull"}};
    TempDir dir;
    io::write_surface(complex, dir / "bad.ply");
    const auto result = run_cli("tm-tetra", {"-i", (dir / "bad.ply").string(), "-o", (dir / "mesh.msh").string()});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("tm-tetra: error: "), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("scalp"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("skull"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find(" mm"), std::string::npos) << result.err;
    EXPECT_EQ(dir.files(), std::vector<std::string>{"bad.ply"}) << "no mesh may be left behind";
}

TEST(TetraCli, BadOptionsAndFilesExitTwoWithOneLine)
{
    TempDir dir;
    make_surface(dir, "thin", "4");
    const auto surface = (dir / "surface.ply").string();
    const auto unknown =
        run_cli("tm-tetra", {"-i", surface, "-o", (dir / "m.msh").string(), "--max-volume", "liver=3"});
    EXPECT_EQ(unknown.exit_code, 2);
    EXPECT_NE(unknown.err.find("unknown tissue \"liver\""), std::string::npos) << unknown.err;
    EXPECT_NE(unknown.err.find("1 shell"), std::string::npos) << "the known tissues are listed: " << unknown.err;
    const auto format = run_cli("tm-tetra", {"-i", surface, "-o", (dir / "m.xyz").string()});
    EXPECT_EQ(format.exit_code, 2);
    EXPECT_NE(format.err.find("unknown mesh format"), std::string::npos) << format.err;
    std::ofstream(dir / "broken.msh") << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n";
    const auto truncated = run_cli("tm-check-mesh", {(dir / "broken.msh").string()});
    EXPECT_EQ(truncated.exit_code, 2);
    EXPECT_NE(truncated.err.find("broken.msh: expected"), std::string::npos) << truncated.err;
}

// Issue 32: --max-volume 65537=2 exited 0 and bounded tissue 1 (the number wrapped to 16 bits).
TEST(TetraCli, MaxVolumeFor65537IsAnErrorNamingTheRangeNotABoundOnTissue1)
{
    TempDir dir;
    make_surface(dir, "thin", "4");
    for (const char* option : {"--max-volume", "--max-edge-mm"}) {
        const auto result = run_cli(
            "tm-tetra", {"-i", (dir / "surface.ply").string(), "-o", (dir / "m.msh").string(), option, "65537=2"});
        EXPECT_EQ(result.exit_code, 2) << option;
        EXPECT_NE(result.err.find(concat(option, " 65537=2: tissue 65537 is not a label number; labels are 0..65535")),
                  std::string::npos)
            << result.err;
        EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << "one line: " << result.err;
    }
    const auto absent = run_cli(
        "tm-tetra", {"-i", (dir / "surface.ply").string(), "-o", (dir / "m.msh").string(), "--max-volume", "7=2"});
    EXPECT_EQ(absent.exit_code, 2);
    EXPECT_NE(absent.err.find("surface.ply has no tissue 7"), std::string::npos) << absent.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "m.msh")) << "no mesh may be left behind";
    const auto any_case = run_cli("tm-tetra", {"-i", (dir / "surface.ply").string(), "-o", (dir / "m.msh").string(),
                                               "--max-volume", "SHELL=50", "-q"});
    EXPECT_EQ(any_case.exit_code, 0) << any_case.err;
}

// Issue 32: options out of range are refused with one line naming option, value and range, not clamped.
TEST(TetraCli, OptimiseAndInsertBelowOutOfRangeAreErrorsNotClamped)
{
    TempDir dir;
    make_surface(dir, "thin", "4");
    const auto optimise =
        run_cli("tm-tetra", {"-i", (dir / "surface.ply").string(), "-o", (dir / "m.msh").string(), "--optimise", "11"});
    EXPECT_EQ(optimise.exit_code, 2);
    EXPECT_NE(optimise.err.find("--optimise"), std::string::npos) << optimise.err;
    EXPECT_NE(optimise.err.find("11"), std::string::npos) << optimise.err;
    EXPECT_NE(optimise.err.find("not in range 0 to 10"), std::string::npos) << optimise.err;
    const auto insert = run_cli("tm-tetra", {"-i", (dir / "surface.ply").string(), "-o", (dir / "m.msh").string(),
                                             "--improve-insert-below-deg", "30", "--improve-target-deg", "20"});
    EXPECT_EQ(insert.exit_code, 2);
    EXPECT_NE(insert.err.find("--improve-insert-below-deg 30 is above --improve-target-deg 20"), std::string::npos)
        << insert.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "m.msh")) << "no mesh may be left behind";
}

} // namespace
} // namespace tissuemesh

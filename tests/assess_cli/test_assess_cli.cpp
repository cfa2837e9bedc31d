// tm-assess as a user runs it: outputs, summary figures, relabelling, and bad input.
#include <algorithm>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/tet_mesh_io.h"
#include "io/write_label_image.h"
#include "tests/support/cli.h"
#include "volume/mark_interfaces.h"

namespace tissuemesh {
namespace {

using testing::read_text;
using testing::run_cli;
using testing::TempDir;

/// The cube [0, 2] mm^3 as 6 Kuhn tets (tissue 1, "inner") on 0.5 mm voxels where the plane i == 3 is
/// tissue 2 ("outer"): tet 0 (x >= y >= z) holds 10 + 10 voxels (see tests/assess), 16 voxels of tissue 2
/// in all. Tet 0 is set to tissue 2 so that --relabel has a tie to keep.
void write_inputs(const TempDir& dir)
{
    TetMesh mesh;
    for (int c = 0; c < 8; ++c) mesh.vertices.push_back({2.0 * (c & 1), 2.0 * (c >> 1 & 1), 2.0 * (c >> 2 & 1)});
    const int axes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (const auto& order : axes) {
        const std::uint32_t a = 1u << order[0], b = a | 1u << order[1];
        mesh.tets.push_back({0, a, b, 7});
        mesh.tet_labels.push_back(1);
        if (signed_volume(mesh, mesh.tets.size() - 1) < 0) std::swap(mesh.tets.back()[2], mesh.tets.back()[3]);
    }
    mesh.tet_labels[0] = 2;
    mesh.names = {{1, "inner"}, {2, "outer"}};
    volume::mark_interfaces(mesh);
    io::write_tet_mesh(mesh, dir / "cube.msh");
    LabelImage image({7, 7, 7}, {0.5, 0.5, 0.5});
    for (std::size_t k = 0; k < 4; ++k)
        for (std::size_t j = 0; j < 4; ++j)
            for (std::size_t i = 0; i < 4; ++i) image.at(i, j, k) = i == 3 ? 2 : 1;
    io::write_label_image(image, dir / "cube.nii.gz");
}

nlohmann::json read_json(const std::filesystem::path& path)
{
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

TEST(AssessCli, WritesCellDataAndSummary)
{
    TempDir dir;
    write_inputs(dir);
    const auto result =
        run_cli("tm-assess", {"-i", (dir / "cube.msh").string(), "--image", (dir / "cube.nii.gz").string(), "-o",
                              (dir / "out.vtu").string(), "--json", (dir / "s.json").string(), "-q"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const std::string vtu = read_text(dir / "out.vtu");
    EXPECT_NE(vtu.find("NumberOfCells=\"6\""), std::string::npos);
    for (const char* field : {"tissue", "majority", "error_volume_mm3", "quality_key", "voxel_count",
                              "min_dihedral_deg", "radius_edge_ratio"})
        EXPECT_NE(vtu.find(std::string("Name=\"") + field + "\""), std::string::npos) << field;
    const nlohmann::json s = read_json(dir / "s.json");
    EXPECT_EQ(s["voxels_inside"].get<int>(), 64);
    EXPECT_EQ(s["sampled_tets"].get<int>(), 0);
    // Tet 0 (tissue 2) holds 10 voxels of tissue 1; the 5 other tets hold the remaining 6 voxels of tissue 2.
    EXPECT_EQ(s["total_error_volume_mm3"].get<double>(), 16 * 0.125);
    EXPECT_EQ(s["tissues"]["2"]["name"].get<std::string>(), "outer");
    // Tissue 2: 16 image voxels, 20 meshed (tet 0), 10 agreeing.
    EXPECT_DOUBLE_EQ(s["tissues"]["2"]["dice"].get<double>(), 2.0 * 10 / (16 + 20));
}

TEST(AssessCli, RelabelWritesTheMajorityMeshWithRebuiltInterfaces)
{
    // Tissue 2 voxels (the plane x = 3): 10 in tet 0 (x >= y >= z, y >= z) against 10 of tissue 1, and 6 in
    // tet 1 (x >= z > y, z > y) against 4; no other tet reaches x = 3.
    TempDir dir;
    write_inputs(dir);
    auto relabel = [&](const std::string& out, const std::vector<std::string>& extra) {
        std::vector<std::string> args{"-i",
                                      (dir / "cube.msh").string(),
                                      "--image",
                                      (dir / "cube.nii.gz").string(),
                                      "-o",
                                      (dir / out).string(),
                                      "--relabel",
                                      "--json",
                                      (dir / "s.json").string(),
                                      "-q"};
        args.insert(args.end(), extra.begin(), extra.end());
        const auto result = run_cli("tm-assess", args);
        EXPECT_EQ(result.exit_code, 0) << result.err;
        const auto check = run_cli("tm-check-mesh", {(dir / out).string(), "-q"});
        EXPECT_EQ(check.exit_code, 0) << out << ": " << check.out;
        return io::read_tet_mesh(dir / out);
    };
    // Unit weights: tet 0 keeps tissue 2 (a 10/10 tie stays with the current tissue), tet 1 becomes 2 (6 > 4).
    EXPECT_EQ(relabel("plain.msh", {}).tet_labels, (std::vector<Label>{2, 2, 1, 1, 1, 1}));
    EXPECT_EQ(read_json(dir / "s.json")["relabelled_tets"].get<int>(), 1);
    // Weight 2 on tissue 1: 20 > 10 and 8 > 6, every tet becomes 1 and only boundary faces remain (2 per side).
    const TetMesh inner = relabel("inner.msh", {"--priority", "inner=2"});
    EXPECT_EQ(inner.tet_labels, std::vector<Label>(6, 1));
    EXPECT_EQ(inner.faces.size(), 12u);
    EXPECT_EQ(read_json(dir / "s.json")["relabelled_tets"].get<int>(), 1);
    EXPECT_EQ(read_json(dir / "s.json")["total_error_volume_mm3"].get<double>(), 16 * 0.125);
}

// Issue 32: tm-assess takes the priority tm-extract was given, in tm-extract's words (TISSUE=N or auto), so that
// its sub-voxel samples see the tissues of the priority rule's split cubes; the summary says which it used.
TEST(AssessCli, ExtractPriorityTakesTmExtractsSyntaxAndIsInTheSummary)
{
    TempDir dir;
    write_inputs(dir);
    const auto assess = [&](const std::string& priority) {
        const auto result =
            run_cli("tm-assess", {"-i", (dir / "cube.msh").string(), "--image", (dir / "cube.nii.gz").string(), "-o",
                                  (dir / "out.vtu").string(), "--extract-priority", priority, "--json",
                                  (dir / "s.json").string(), "-q"});
        EXPECT_EQ(result.exit_code, 0) << result.err;
        return read_json(dir / "s.json")["extract_priority"];
    };
    EXPECT_EQ(assess("outer=2,1=1"), (nlohmann::json{{"1", 1}, {"2", 2}}));
    // auto: the one-voxel plane of tissue 2 ranks above the 3-voxel block of tissue 1; background 0 is not ranked.
    const nlohmann::json ranked = assess("auto");
    EXPECT_EQ(ranked.size(), 2u) << ranked;
    EXPECT_GT(ranked["2"].get<int>(), ranked["1"].get<int>()) << ranked;
    const auto plain =
        run_cli("tm-assess", {"-i", (dir / "cube.msh").string(), "--image", (dir / "cube.nii.gz").string(), "-o",
                              (dir / "out.vtu").string(), "--json", (dir / "s.json").string(), "-q"});
    ASSERT_EQ(plain.exit_code, 0) << plain.err;
    EXPECT_EQ(read_json(dir / "s.json")["extract_priority"], nlohmann::json::object());
}

TEST(AssessCli, BadInputExitsTwoWithOneLineAndNoOutput)
{
    TempDir dir;
    write_inputs(dir);
    const std::string mesh = (dir / "cube.msh").string(), image = (dir / "cube.nii.gz").string();
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"-i", mesh, "--image", (dir / "missing.nii.gz").string(), "-o", (dir / "out.vtu").string()},
         "missing.nii.gz"},
        {{"-i", (dir / "missing.msh").string(), "--image", image, "-o", (dir / "out.vtu").string()}, "missing.msh"},
        {{"-i", mesh, "--image", image, "-o", (dir / "out.vtu").string(), "--priority", "liver=2"},
         "unknown tissue \"liver\""},
        {{"-i", mesh, "--image", image, "-o", (dir / "out.vtu").string(), "--priority", "outer=-1"},
         "not tissue=positive"},
        {{"-i", mesh, "--image", image, "-o", (dir / "out.vtu").string(), "--extract-priority", "outer=1.5"},
         "--extract-priority outer=1.5: expected TISSUE=INTEGER"},
        {{"-i", mesh, "--image", image, "-o", (dir / "out.vtu").string(), "--extract-priority", "bone=1"},
         "--extract-priority bone=1: unknown tissue \"bone\""},
        {{"-i", mesh, "--image", image, "-o", (dir / "out.vtu").string(), "--extract-priority", "auto,outer=1"},
         "--extract-priority auto ranks every tissue itself"},
        {{"-i", mesh, "--image", image, "-o", (dir / "out.xyz").string()}, "unknown output format"},
    };
    for (const auto& [args, expected] : cases) {
        const auto result = run_cli("tm-assess", args);
        EXPECT_EQ(result.exit_code, 2) << expected;
        EXPECT_EQ(result.err.rfind("tm-assess: error: ", 0), 0u) << result.err;
        EXPECT_NE(result.err.find(expected), std::string::npos) << result.err;
        EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    }
    EXPECT_EQ(dir.files(), (std::vector<std::string>{"cube.msh", "cube.nii.gz"})) << "no output may be left behind";
}

} // namespace
} // namespace tissuemesh

// tm-check-surface as a user runs it: exit codes and what it says.
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/surface_io.h"
#include "tests/support/cli.h"
#include "tests/support/complexes.h"

namespace tissuemesh {
namespace {

using testing::add_box;
using testing::read_json;
using testing::run_cli;
using testing::TempDir;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// A box of tissue `inside` against `outside` (testing::add_box).
struct Box {
    Vec3 low, high;
    Label inside, outside;
};

/// Writes the boxes, tissues named `names`, to `path` (a .ply) and returns the path as a program argument.
std::string write_boxes(const std::filesystem::path& path, const std::vector<Box>& boxes, const TissueNames& names)
{
    InterfaceComplex complex;
    for (const Box& box : boxes) add_box(complex, box.low, box.high, box.inside, box.outside);
    complex.names = names;
    io::write_surface(complex, path);
    return path.string();
}

TEST(CheckSurfaceCli, NestedBoxesAreFitAndExitZero)
{
    TempDir dir;
    const std::string head = write_boxes(dir / "head.ply", {{{0, 0, 0}, {3, 3, 3}, 1, 0}, {{1, 1, 1}, {2, 2, 2}, 2, 1}},
                                         {{0, "air"}, {1, "skull"}, {2, "brain"}});
    const auto result = run_cli("tm-check-surface", {head, "--json", (dir / "c.json").string()});
    EXPECT_EQ(result.exit_code, 0) << result.out << result.err;
    EXPECT_TRUE(contains(result.out, "fit for tetrahedralization")) << result.out;
    EXPECT_FALSE(contains(result.out, "NOT fit")) << result.out;
    EXPECT_TRUE(contains(result.out, "brain")) << result.out;
    const nlohmann::json summary = read_json(dir / "c.json");
    EXPECT_EQ(summary["fit_for_tetrahedralization"], true);
    EXPECT_EQ(summary["exit_code"], 0);
    EXPECT_EQ(summary["triangles"], 24);
    ASSERT_EQ(summary["tissues"].size(), 3u);
    // Tissues ascend by label: air (minus everything), skull (27 - 1 mm^3), brain (1 mm^3).
    EXPECT_NEAR(summary["tissues"][0]["volume_mm3"].get<double>(), -27.0, 1e-9);
    EXPECT_NEAR(summary["tissues"][1]["volume_mm3"].get<double>(), 26.0, 1e-9);
    EXPECT_NEAR(summary["tissues"][2]["volume_mm3"].get<double>(), 1.0, 1e-9);
    EXPECT_EQ(summary["tissues"][1]["components"], 2); // skull's outer and inner sheets
    // Each tissue fills 90 degrees about its box's edges (the skull 270 about the brain's), 180 about face diagonals.
    EXPECT_NEAR(summary["min_tissue_sector_deg"].get<double>(), 90.0, 1e-9);
}

TEST(CheckSurfaceCli, IntersectingBoxesExitOneNamingTissuesAndPlace)
{
    TempDir dir;
    const std::string crossing =
        write_boxes(dir / "crossing.ply", {{{0, 0, 0}, {2, 2, 2}, 1, 0}, {{1, 1, 1}, {3, 3, 3}, 2, 0}},
                    {{0, "air"}, {1, "scalp"}, {2, "skull"}});
    const auto result =
        run_cli("tm-check-surface", {"-i", crossing, "--max-report", "3", "--json", (dir / "c.json").string()});
    EXPECT_EQ(result.exit_code, 1) << result.out << result.err;
    EXPECT_TRUE(contains(result.out, "NOT fit for tetrahedralization")) << result.out;
    // The one-line error names the kind, the tissues, a location, and what to do next.
    EXPECT_TRUE(contains(result.err, "crossing.ply: not fit for tetrahedralization")) << result.err;
    EXPECT_TRUE(contains(result.err, "patch-intersection")) << result.err;
    EXPECT_TRUE(contains(result.err, "scalp|air triangle")) << result.err;
    EXPECT_TRUE(contains(result.err, "skull|air triangle")) << result.err;
    EXPECT_TRUE(contains(result.err, "near (")) << result.err;
    EXPECT_TRUE(contains(result.err, "re-extract it with tm-extract")) << result.err;
    const nlohmann::json summary = read_json(dir / "c.json");
    EXPECT_EQ(summary["fit_for_tetrahedralization"], false);
    EXPECT_GT(summary["defect_counts"]["patch-intersection"].get<int>(), 3);
    ASSERT_EQ(summary["defects"].size(), 3u); // --max-report 3
    for (const auto& defect : summary["defects"]) {
        // The boxes' surfaces cross only within their overlap [1, 2]^3 (1e-9 mm: rounded construction).
        for (int axis = 0; axis < 3; ++axis) {
            EXPECT_GE(defect["location_mm"][axis].get<double>(), 1 - 1e-9);
            EXPECT_LE(defect["location_mm"][axis].get<double>(), 2 + 1e-9);
        }
    }
}

TEST(CheckSurfaceCli, OpenSurfaceExitsOneWithOpenEdges)
{
    TempDir dir;
    InterfaceComplex complex;
    add_box(complex, {0, 0, 0}, {1, 1, 1}, 1, 0);
    complex.triangles.pop_back();
    complex.sides.pop_back();
    io::write_surface(complex, dir / "hole.ply");
    const auto result = run_cli("tm-check-surface", {(dir / "hole.ply").string()});
    EXPECT_EQ(result.exit_code, 1) << result.out << result.err;
    EXPECT_TRUE(contains(result.err, "6 open-edge")) << result.err;
}

TEST(CheckSurfaceCli, MissingOrUnreadableFileExitsTwo)
{
    TempDir dir;
    const auto missing = run_cli("tm-check-surface", {(dir / "absent.ply").string()});
    EXPECT_EQ(missing.exit_code, 2) << missing.err;
    EXPECT_TRUE(contains(missing.err, "absent.ply")) << missing.err;

    std::ofstream(dir / "garbage.ply") << "this is not a ply file\n";
    const auto garbage = run_cli("tm-check-surface", {(dir / "garbage.ply").string()});
    EXPECT_EQ(garbage.exit_code, 2) << garbage.err;
    EXPECT_TRUE(contains(garbage.err, "garbage.ply")) << garbage.err;

    const auto no_argument = run_cli("tm-check-surface", {});
    EXPECT_EQ(no_argument.exit_code, 2) << no_argument.err;
}

} // namespace
} // namespace tissuemesh

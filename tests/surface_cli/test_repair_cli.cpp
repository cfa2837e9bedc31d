// tm-repair as a user runs it: a broken complex comes out fit with a report of what changed; what it cannot
// fix fails with exit 1 and writes nothing; tm-check-surface points to tm-repair only where it may help.
#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "image/phantom.h"
#include "io/surface_io.h"
#include "io/write_label_image.h"
#include "surface/check_complex.h"
#include "surface/extract_interfaces.h"
#include "tests/support/cli.h"
#include "tests/support/complexes.h"

namespace tissuemesh {
namespace {

using testing::run_cli;
using testing::TempDir;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(RepairCli, BrokenComplexComesOutFitWithAReport)
{
    const TempDir dir;
    const image::Phantom phantom = image::make_phantom("junction", {.voxel_mm = 6.0});
    io::write_label_image(phantom.image, (dir / "j.nii.gz").string());
    InterfaceComplex complex = surface::extract_interfaces(phantom.image);
    const std::size_t triangles = complex.triangle_count();
    testing::flip_triangle(complex, 7);
    complex.add_triangle(complex.triangles[20], complex.sides[20]);
    io::write_surface(complex, (dir / "broken.ply").string());

    const auto check = run_cli("tm-check-surface", {(dir / "broken.ply").string()});
    EXPECT_EQ(check.exit_code, 1);
    EXPECT_TRUE(contains(check.err, "tm-repair may fix it")) << check.err;

    const auto repaired =
        run_cli("tm-repair", {"-i", (dir / "broken.ply").string(), "-o", (dir / "fixed.ply").string(), "--image",
                              (dir / "j.nii.gz").string(), "--gap-mm", "0.1", "--json", (dir / "r.json").string()});
    ASSERT_EQ(repaired.exit_code, 0) << repaired.err;
    const nlohmann::json r = testing::read_json(dir / "r.json");
    EXPECT_EQ(r.at("flipped_triangles").get<std::size_t>(), 1u);
    EXPECT_EQ(r.at("removed_duplicates").get<std::size_t>(), 1u);
    EXPECT_EQ(r.at("triangles_after").get<std::size_t>(), triangles);
    EXPECT_TRUE(r.at("changed").get<bool>());
    ASSERT_EQ(r.at("actions").size(), 2u);
    for (const auto& action : r.at("actions")) {
        EXPECT_TRUE(contains(action.at("description").get<std::string>(), ") mm")) << action;
        EXPECT_EQ(action.at("location_mm").size(), 3u);
        EXPECT_EQ(action.at("tissues").size(), 2u);
    }
    const InterfaceComplex fixed = io::read_surface((dir / "fixed.ply").string());
    EXPECT_EQ(fixed.triangle_count(), triangles);
    EXPECT_TRUE(surface::check_complex(fixed).ok());
    EXPECT_EQ(run_cli("tm-check-surface", {(dir / "fixed.ply").string()}).exit_code, 0);
}

TEST(RepairCli, HolesFailWithExitOneAndNothingWritten)
{
    const TempDir dir;
    InterfaceComplex complex = testing::icosphere(2, 10.0, {0, 0, 0});
    complex.triangles.pop_back();
    complex.sides.pop_back();
    io::write_surface(complex, (dir / "hole.ply").string());
    const auto check = run_cli("tm-check-surface", {(dir / "hole.ply").string()});
    EXPECT_EQ(check.exit_code, 1);
    EXPECT_TRUE(contains(check.err, "tm-repair cannot fix open-edge defects")) << check.err;
    const auto repaired = run_cli("tm-repair", {"-i", (dir / "hole.ply").string(), "-o", (dir / "out.ply").string()});
    EXPECT_EQ(repaired.exit_code, 1);
    EXPECT_TRUE(contains(repaired.err, "open-edge defects remain")) << repaired.err;
    EXPECT_TRUE(contains(repaired.err, "re-extract the interfaces from the label image with tm-extract"))
        << repaired.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.ply"));
}

TEST(RepairCli, RefusesLossyFormatsAndBadOptions)
{
    const TempDir dir;
    io::write_surface(testing::icosphere(1, 10.0, {0, 0, 0}), (dir / "s.ply").string());
    const auto stl = run_cli("tm-repair", {"-i", (dir / "s.ply").string(), "-o", (dir / "out.stl").string()});
    EXPECT_EQ(stl.exit_code, 2);
    EXPECT_TRUE(contains(stl.err, "written as .ply or .vtp")) << stl.err;
    const auto gap =
        run_cli("tm-repair", {"-i", (dir / "s.ply").string(), "-o", (dir / "out.ply").string(), "--gap-mm", "-1"});
    EXPECT_EQ(gap.exit_code, 2);
    EXPECT_TRUE(contains(gap.err, "gap -1 mm must not be negative")) << gap.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.ply"));
}

} // namespace
} // namespace tissuemesh

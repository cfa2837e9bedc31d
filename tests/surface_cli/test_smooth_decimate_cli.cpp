// tm-smooth, tm-decimate and tm-remesh as a user chains them after tm-extract: valid outputs, summaries, refusals.
#include <filesystem>
#include <fstream>
#include <string>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "image/phantom.h"
#include "io/surface_io.h"
#include "io/write_label_image.h"
#include "surface/check_complex.h"
#include "surface/extract_interfaces.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

using testing::run_cli;
using testing::TempDir;

/// The junction phantom at 6 mm (small and quick) written as image and extracted complex.
struct Inputs {
    std::string image, surface;
};

Inputs write_inputs(const TempDir& dir)
{
    const image::Phantom phantom = image::make_phantom("junction", {.voxel_mm = 6.0});
    Inputs inputs{(dir / "j.nii.gz").string(), (dir / "j.ply").string()};
    io::write_label_image(phantom.image, inputs.image);
    io::write_surface(surface::extract_interfaces(phantom.image), inputs.surface);
    return inputs;
}

TEST(SmoothDecimateCli, ChainKeepsTheComplexFitAndReportsCounts)
{
    const TempDir dir;
    const Inputs in = write_inputs(dir);
    const auto smooth = run_cli("tm-smooth", {"-i", in.surface, "--image", in.image, "-o", (dir / "s.ply").string(),
                                              "--json", (dir / "s.json").string()});
    ASSERT_EQ(smooth.exit_code, 0) << smooth.err;
    const nlohmann::json s = testing::read_json((dir / "s.json").string());
    EXPECT_GT(s.at("moves").get<std::size_t>(), 0u);
    const auto decimate = run_cli("tm-decimate", {"-i", (dir / "s.ply").string(), "-o", (dir / "d.ply").string(),
                                                  "--json", (dir / "d.json").string(), "--max-distance-mm", "3"});
    ASSERT_EQ(decimate.exit_code, 0) << decimate.err;
    const nlohmann::json d = testing::read_json((dir / "d.json").string());
    EXPECT_LT(d.at("triangles_after").get<std::size_t>(), d.at("triangles_before").get<std::size_t>());
    EXPECT_LE(d.at("max_distance_mm").get<double>(), 3.0);
    const InterfaceComplex result = io::read_surface((dir / "d.ply").string());
    EXPECT_EQ(result.triangle_count(), d.at("triangles_after").get<std::size_t>());
    EXPECT_TRUE(surface::check_complex(result).ok());
    const auto remeshed =
        run_cli("tm-remesh", {"-i", (dir / "d.ply").string(), "-o", (dir / "r.ply").string(), "--edge-mm", "12",
                              "--edge-mm-pair", "2:3=9", "--json", (dir / "r.json").string()});
    ASSERT_EQ(remeshed.exit_code, 0) << remeshed.err;
    const nlohmann::json r = testing::read_json(dir / "r.json");
    EXPECT_GT(r.at("triangles_after").get<std::size_t>(), 0u);
    EXPECT_TRUE(surface::check_complex(io::read_surface((dir / "r.ply").string())).ok());
    const auto bad_pair =
        run_cli("tm-remesh", {"-i", (dir / "d.ply").string(), "-o", (dir / "x.ply").string(), "--edge-mm-pair", "2=9"});
    EXPECT_EQ(bad_pair.exit_code, 2);
    EXPECT_NE(bad_pair.err.find("expected TISSUE:TISSUE=MM"), std::string::npos) << bad_pair.err;
    const auto sized = run_cli("tm-decimate", {"-i", (dir / "s.ply").string(), "-o", (dir / "z.ply").string(), "--mode",
                                               "size", "--target-edge-mm", "12"});
    EXPECT_EQ(sized.exit_code, 0) << sized.err;
}

TEST(SmoothDecimateCli, BoundsTheDistanceInVoxelsOfTheImage)
{
    const TempDir dir;
    const Inputs in = write_inputs(dir); // 6 mm voxels
    const auto voxels =
        run_cli("tm-decimate", {"-i", in.surface, "-o", (dir / "v.ply").string(), "--max-distance-voxels", "0.25",
                                "--image", in.image, "--json", (dir / "v.json").string()});
    ASSERT_EQ(voxels.exit_code, 0) << voxels.err;
    const nlohmann::json v = testing::read_json((dir / "v.json").string());
    EXPECT_DOUBLE_EQ(v.at("voxel_mm").get<double>(), 6.0);
    EXPECT_DOUBLE_EQ(v.at("max_distance_bound_mm").get<double>(), 1.5);
    EXPECT_LE(v.at("max_distance_mm").get<double>(), 1.5);
    EXPECT_LT(v.at("triangles_after").get<std::size_t>(), v.at("triangles_before").get<std::size_t>());
    // The same decimation as the bound in mm.
    const auto mm =
        run_cli("tm-decimate", {"-i", in.surface, "-o", (dir / "m.ply").string(), "--max-distance-mm", "1.5"});
    ASSERT_EQ(mm.exit_code, 0) << mm.err;
    const InterfaceComplex by_voxels = io::read_surface((dir / "v.ply").string());
    const InterfaceComplex by_mm = io::read_surface((dir / "m.ply").string());
    EXPECT_EQ(by_voxels.vertices, by_mm.vertices);
    EXPECT_EQ(by_voxels.triangles, by_mm.triangles);
    // Refused, nothing written: no image; an image for nothing; both bounds; an image that is no image.
    const std::string out = (dir / "out.ply").string();
    const auto no_image = run_cli("tm-decimate", {"-i", in.surface, "-o", out, "--max-distance-voxels", "0.25"});
    EXPECT_EQ(no_image.exit_code, 2);
    EXPECT_NE(no_image.err.find("give --image"), std::string::npos) << no_image.err;
    const auto idle_image = run_cli("tm-decimate", {"-i", in.surface, "-o", out, "--image", in.image});
    EXPECT_EQ(idle_image.exit_code, 2);
    EXPECT_NE(idle_image.err.find("only for --max-distance-voxels"), std::string::npos) << idle_image.err;
    const auto both = run_cli("tm-decimate", {"-i", in.surface, "-o", out, "--max-distance-voxels", "0.25",
                                              "--max-distance-mm", "1", "--image", in.image});
    EXPECT_EQ(both.exit_code, 2);
    const auto not_image =
        run_cli("tm-decimate", {"-i", in.surface, "-o", out, "--max-distance-voxels", "0.25", "--image", in.surface});
    EXPECT_EQ(not_image.exit_code, 2);
    EXPECT_NE(not_image.err.find("j.ply"), std::string::npos) << not_image.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(SmoothDecimateCli, RemeshKeepsTheVoxelsSidesOfTheImageItIsGiven)
{
    const TempDir dir;
    const Inputs in = write_inputs(dir); // 6 mm voxels
    const auto kept =
        run_cli("tm-remesh", {"-i", in.surface, "-o", (dir / "k.ply").string(), "--edge-mm", "12", "--keep-voxel-sides",
                              "--image", in.image, "--json", (dir / "k.json").string()});
    ASSERT_EQ(kept.exit_code, 0) << kept.err;
    const nlohmann::json k = testing::read_json((dir / "k.json").string());
    EXPECT_TRUE(k.at("keep_voxel_sides").get<bool>());
    EXPECT_GT(k.at("refused_by_voxels").get<std::size_t>(), 0u);
    EXPECT_TRUE(surface::check_complex(io::read_surface((dir / "k.ply").string())).ok());
    // Refused, nothing written: the flag without an image, an image without the flag.
    const std::string out = (dir / "out.ply").string();
    const auto no_image = run_cli("tm-remesh", {"-i", in.surface, "-o", out, "--edge-mm", "12", "--keep-voxel-sides"});
    EXPECT_EQ(no_image.exit_code, 2);
    EXPECT_NE(no_image.err.find("give --image"), std::string::npos) << no_image.err;
    const auto idle_image = run_cli("tm-remesh", {"-i", in.surface, "-o", out, "--edge-mm", "12", "--image", in.image});
    EXPECT_EQ(idle_image.exit_code, 2);
    EXPECT_NE(idle_image.err.find("only for --keep-voxel-sides"), std::string::npos) << idle_image.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(SmoothDecimateCli, RefusesUnfitInputBadOptionsAndLossyFormats)
{
    const TempDir dir;
    const Inputs in = write_inputs(dir);
    // A complex with one triangle removed has holes: refused before any work, nothing written.
    InterfaceComplex broken = io::read_surface(in.surface);
    broken.triangles.pop_back();
    broken.sides.pop_back();
    io::write_surface(broken, (dir / "broken.ply").string());
    const auto unfit = run_cli("tm-decimate", {"-i", (dir / "broken.ply").string(), "-o", (dir / "out.ply").string()});
    EXPECT_EQ(unfit.exit_code, 2);
    EXPECT_NE(unfit.err.find("broken.ply: not fit for tetrahedralization"), std::string::npos) << unfit.err;
    EXPECT_FALSE(std::filesystem::exists((dir / "out.ply").string()));
    const auto stl = run_cli("tm-smooth", {"-i", in.surface, "--image", in.image, "-o", (dir / "out.stl").string()});
    EXPECT_EQ(stl.exit_code, 2);
    EXPECT_NE(stl.err.find("written as .ply or .vtp"), std::string::npos) << stl.err;
    const auto size = run_cli("tm-decimate", {"-i", in.surface, "-o", (dir / "out.ply").string(), "--mode", "size"});
    EXPECT_EQ(size.exit_code, 2);
    EXPECT_NE(size.err.find("size mode needs a target edge length"), std::string::npos) << size.err;
    const auto both = run_cli("tm-decimate", {"-i", in.surface, "-o", (dir / "out.ply").string(), "--mode", "size",
                                              "--target-edge-mm", "2", "--max-edge-mm", "3"});
    EXPECT_EQ(both.exit_code, 2);
    EXPECT_NE(both.err.find("bounds curvature mode only"), std::string::npos) << both.err;
    const auto lambda = run_cli("tm-smooth", {"-i", in.surface, "--image", in.image, "-o", (dir / "out.ply").string(),
                                              "--max-depth-voxels", "3"});
    EXPECT_EQ(lambda.exit_code, 2);
    EXPECT_FALSE(std::filesystem::exists((dir / "out.ply").string()));
}

/// The "tissuemesh-checked ..." comment of a .ply header ("" when there is none).
std::string stamp_of(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::string line;
    while (std::getline(in, line) && line != "end_header")
        if (line.rfind("comment tissuemesh-checked ", 0) == 0) return line.substr(8);
    return "";
}

TEST(SmoothDecimateCli, CheckStampSkipsTheSecondCheckOfTheSameComplexOnly)
{
    const TempDir dir;
    const Inputs in = write_inputs(dir);
    const std::string smoothed = (dir / "s.ply").string();
    const auto smooth = run_cli(
        "tm-smooth", {"-i", in.surface, "--image", in.image, "-o", smoothed, "--json", (dir / "s.json").string()});
    ASSERT_EQ(smooth.exit_code, 0) << smooth.err;
    // tm-extract writes no stamp: tm-smooth checked its input; its output carries the stamp of its check.
    EXPECT_TRUE(testing::read_json(dir / "s.json").at("input_checked").get<bool>());
    const std::string stamp = stamp_of(smoothed);
    EXPECT_EQ(stamp.rfind("tissuemesh-checked ", 0), 0u) << stamp;
    const auto skipped = run_cli("tm-decimate", {"-i", smoothed, "-o", (dir / "d.ply").string(), "--max-distance-mm",
                                                 "3", "--json", (dir / "d.json").string()});
    ASSERT_EQ(skipped.exit_code, 0) << skipped.err;
    EXPECT_FALSE(testing::read_json(dir / "d.json").at("input_checked").get<bool>());
    EXPECT_NE(skipped.err.find("input check skipped: " + smoothed + " carries the stamp"), std::string::npos)
        << skipped.err;
    const auto forced = run_cli("tm-decimate", {"-i", smoothed, "-o", (dir / "d2.ply").string(), "--max-distance-mm",
                                                "3", "--check-input", "--json", (dir / "d2.json").string()});
    ASSERT_EQ(forced.exit_code, 0) << forced.err;
    EXPECT_TRUE(testing::read_json(dir / "d2.json").at("input_checked").get<bool>());
    // The same stamp on a changed complex (a triangle less: holes) is not trusted: the check runs and refuses.
    InterfaceComplex broken = io::read_surface(smoothed);
    broken.triangles.pop_back();
    broken.sides.pop_back();
    io::write_surface(broken, (dir / "broken.ply").string(), {stamp});
    ASSERT_EQ(stamp_of((dir / "broken.ply").string()), stamp);
    const auto unfit = run_cli("tm-decimate", {"-i", (dir / "broken.ply").string(), "-o", (dir / "out.ply").string()});
    EXPECT_EQ(unfit.exit_code, 2);
    EXPECT_NE(unfit.err.find("broken.ply: not fit for tetrahedralization"), std::string::npos) << unfit.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.ply"));
    // So is a moved vertex (the geometry is part of the digest).
    InterfaceComplex moved = io::read_surface(smoothed);
    moved.vertices[0][0] += 1e-9;
    io::write_surface(moved, (dir / "moved.ply").string(), {stamp});
    const auto rechecked = run_cli("tm-decimate", {"-i", (dir / "moved.ply").string(), "-o", (dir / "m.ply").string(),
                                                   "--max-distance-mm", "3", "--json", (dir / "m.json").string()});
    ASSERT_EQ(rechecked.exit_code, 0) << rechecked.err;
    EXPECT_TRUE(testing::read_json(dir / "m.json").at("input_checked").get<bool>());
}

} // namespace
} // namespace tissuemesh

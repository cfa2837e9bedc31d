// tm-snake as a user runs it: nested snakes through tm-check-surface and tm-tetra, summaries, refusals.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "image/phantom.h"
#include "io/surface_io.h"
#include "io/write_label_image.h"
#include "surface/check_complex.h"
#include "tests/io/make_test_images.h"
#include "tests/support/cli.h"
#include "tests/support/phantom_distance.h"

namespace tissuemesh {
namespace {

using testing::run_cli;
using testing::TempDir;

/// The phantom as NIfTI (which keeps no names) and its names as a --labels table.
std::string write_spheres4(const TempDir& dir, double voxel_mm)
{
    const std::string path = (dir / "spheres4.nii.gz").string();
    io::write_label_image(image::make_phantom("spheres4", {.voxel_mm = voxel_mm}).image, path);
    std::ofstream(dir / "names.json") << R"({"1": "scalp", "2": "skull", "3": "csf", "4": "brain"})";
    return path;
}

/// Nested snakes by tissue name, then the two steps that must accept them.
void nested_through_check_and_tetra(double voxel_mm, const std::string& tissues, const std::string& edge_mm)
{
    const TempDir dir;
    const std::string image = write_spheres4(dir, voxel_mm);
    const std::string out = (dir / "nested.ply").string();
    const auto snake = run_cli("tm-snake", {"-i", image, "--labels", (dir / "names.json").string(), "--nested", tissues,
                                            "--edge-mm", edge_mm, "-o", out, "--json", (dir / "snake.json").string()});
    ASSERT_EQ(snake.exit_code, 0) << snake.err;
    const nlohmann::json s = testing::read_json(dir / "snake.json");
    EXPECT_TRUE(s.at("converged").get<bool>());
    EXPECT_LT(s.at("iterations").get<std::size_t>(), s.at("max_iterations").get<std::size_t>());
    EXPECT_LT(s.at("last_max_motion_mm").get<double>(), s.at("tolerance_mm").get<double>());
    const InterfaceComplex complex = io::read_surface(out);
    EXPECT_EQ(complex.triangle_count(), s.at("triangles").get<std::size_t>());
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = voxel_mm});
    const testing::DistanceFigures figures = testing::phantom_distances(phantom, complex);
    EXPECT_LT(figures.mean_voxels, 0.3);
    EXPECT_LT(figures.max_voxels, 0.8);
    const auto check = run_cli("tm-check-surface", {out});
    EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
    const auto tetra = run_cli("tm-tetra", {"-i", out, "-o", (dir / "nested.msh").string()});
    EXPECT_EQ(tetra.exit_code, 0) << tetra.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "nested.msh"));
}

TEST(SnakeCli, NestedScalpSkullAt4mmPassCheckAndTetra) { nested_through_check_and_tetra(4.0, "scalp,skull", "8"); }

TEST(SnakeCli, LongNestedSpheres4At2mmPassCheckAndTetra)
{
    nested_through_check_and_tetra(2.0, "scalp,skull,csf,brain", "4");
}

TEST(SnakeCli, SphereStartAndIterationCapAreReported)
{
    const TempDir dir;
    const std::string image = write_spheres4(dir, 4.0);
    const auto capped =
        run_cli("tm-snake", {"-i", image, "--tissue", "1", "--init", "sphere", "--centre", "0,0,0", "--radius", "70",
                             "--iterations", "3", "-o", (dir / "c.vtp").string(), "--json", (dir / "c.json").string()});
    ASSERT_EQ(capped.exit_code, 0) << capped.err;
    const nlohmann::json c = testing::read_json(dir / "c.json");
    EXPECT_FALSE(c.at("converged").get<bool>());
    EXPECT_EQ(c.at("iterations").get<std::size_t>(), 3u);
    // Three steps of at most half a voxel (2 mm) from 70 mm: the snake is still on its way to 92 mm.
    EXPECT_GT(c.at("last_max_motion_mm").get<double>(), c.at("tolerance_mm").get<double>());
    EXPECT_NE(capped.err.find("stopped at the cap"), std::string::npos) << capped.err;
    EXPECT_TRUE(surface::check_complex(io::read_surface((dir / "c.vtp").string())).ok());
    // The capped surface, read back as the start, settles on the scalp sphere.
    const auto resumed = run_cli("tm-snake", {"-i", image, "--tissue", "1", "--init", (dir / "c.vtp").string(), "-o",
                                              (dir / "r.ply").string(), "--json", (dir / "r.json").string()});
    ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
    EXPECT_TRUE(testing::read_json(dir / "r.json").at("converged").get<bool>());
    InterfaceComplex settled = io::read_surface((dir / "r.ply").string());
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = 4.0});
    EXPECT_LT(testing::phantom_distances(phantom, settled).mean_voxels, 0.3);
}

/// A grey image in NIfTI as a scanner writes it: int16 values with scl_slope 0.01 (so the stored integers
/// carry fractions), 28^3 voxels of 1.5 mm centred on the origin, value 20 - r (r in mm from the centre): the
/// iso-surface at 8 is the sphere of radius 12 mm.
TEST(SnakeCli, GreyNiftiSettlesOnItsIsoSphere)
{
    const TempDir dir;
    testing::NiftiSpec spec;
    spec.dims[1] = spec.dims[2] = spec.dims[3] = 28;
    spec.spacing[0] = spec.spacing[1] = spec.spacing[2] = 1.5f;
    spec.datatype = 4;
    spec.bitpix = 16;
    spec.scale_slope = 0.01f;
    for (int axis = 0; axis < 3; ++axis) spec.quatern[3 + axis] = -13.5f * 1.5f;
    std::vector<std::int16_t> stored;
    for (int k = 0; k < 28; ++k)
        for (int j = 0; j < 28; ++j)
            for (int i = 0; i < 28; ++i) {
                const double r =
                    1.5 * std::sqrt((i - 13.5) * (i - 13.5) + (j - 13.5) * (j - 13.5) + (k - 13.5) * (k - 13.5));
                stored.push_back(static_cast<std::int16_t>(std::lround((20 - r) / 0.01)));
            }
    testing::write_nifti(dir / "ball.nii", spec, testing::voxel_bytes(stored));
    const auto run = run_cli("tm-snake", {"-i", (dir / "ball.nii").string(), "--grey", "--iso", "8", "--init", "sphere",
                                          "--centre", "0,0,0", "--radius", "16", "-o", (dir / "ball.ply").string(),
                                          "--json", (dir / "ball.json").string()});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_TRUE(testing::read_json(dir / "ball.json").at("converged").get<bool>());
    const InterfaceComplex surface = io::read_surface((dir / "ball.ply").string());
    ASSERT_TRUE(surface::check_complex(surface).ok());
    // Trilinear interpolation of 20 - r bends the level set by at most a few hundredths of a voxel here.
    double mean = 0, largest = 0;
    for (const Vec3& p : surface.vertices) {
        const double off = std::abs(norm(p) - 12.0) / 1.5;
        mean += off;
        largest = std::max(largest, off);
    }
    mean /= static_cast<double>(surface.vertices.size());
    std::cout << "[ figures  ] grey NIfTI ball: " << surface.vertices.size() << " vertices, mean " << mean << " max "
              << largest << " voxel from r = 12 mm\n";
    EXPECT_LT(mean, 0.1) << "voxels";
    EXPECT_LT(largest, 0.3) << "voxels";
}

TEST(SnakeCli, RefusalsNameTheProblemAndLeaveNothing)
{
    const TempDir dir;
    const std::string image = write_spheres4(dir, 6.0);
    const std::string out = (dir / "x.ply").string();
    const auto none = run_cli("tm-snake", {"-i", image, "-o", out});
    EXPECT_EQ(none.exit_code, 2);
    EXPECT_NE(none.err.find("choose one of --tissue"), std::string::npos) << none.err;
    const auto unknown = run_cli("tm-snake", {"-i", image, "--tissue", "bone", "-o", out});
    EXPECT_EQ(unknown.exit_code, 2);
    EXPECT_NE(unknown.err.find("--tissue: unknown tissue \"bone\""), std::string::npos) << unknown.err;
    EXPECT_NE(unknown.err.find("are 0, 1, 2, 3, 4"), std::string::npos)
        << "the known tissues are listed: " << unknown.err;
    const auto missing = run_cli("tm-snake", {"-i", image, "--tissue", "7", "-o", out});
    EXPECT_EQ(missing.exit_code, 2);
    EXPECT_NE(missing.err.find("has no tissue 7"), std::string::npos) << missing.err;
    const auto sphere = run_cli("tm-snake", {"-i", image, "--nested", "1,2", "--init", "sphere", "--centre", "0,0,0",
                                             "--radius", "50", "-o", out});
    EXPECT_EQ(sphere.exit_code, 2);
    EXPECT_NE(sphere.err.find("--init sphere needs one snake"), std::string::npos) << sphere.err;
    const auto stl = run_cli("tm-snake", {"-i", image, "--tissue", "1", "-o", (dir / "x.stl").string()});
    EXPECT_EQ(stl.exit_code, 2);
    EXPECT_NE(stl.err.find("written as .ply or .vtp"), std::string::npos) << stl.err;
    std::ofstream(dir / "grey.png") << "not an image";
    const auto grey = run_cli("tm-snake", {"-i", (dir / "grey.png").string(), "--grey", "--iso", "1", "-o", out});
    EXPECT_EQ(grey.exit_code, 2);
    EXPECT_NE(grey.err.find("unknown grey image format '.png'"), std::string::npos) << grey.err;
    std::filesystem::remove(dir / "grey.png");
    const auto weight = run_cli("tm-snake", {"-i", image, "--tissue", "1", "--tension", "3", "-o", out});
    EXPECT_EQ(weight.exit_code, 2);
    EXPECT_NE(weight.err.find("must lie in [0, 1]"), std::string::npos) << weight.err;
    EXPECT_EQ(dir.files(), (std::vector<std::string>{"names.json", "spheres4.nii.gz"}));
}

} // namespace
} // namespace tissuemesh

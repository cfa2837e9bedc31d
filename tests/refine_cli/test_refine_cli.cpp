// tm-refine as a user runs it: Delaunay-only and constrained runs, the log, the plot, the summary, bad input.
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

#include "image/phantom.h"
#include "io/tet_mesh_io.h"
#include "io/write_label_image.h"
#include "surface/extract_interfaces.h"
#include "tests/support/cli.h"
#include "volume/check_mesh.h"
#include "volume/tetrahedralize.h"

namespace tissuemesh {
namespace {

using testing::read_json;
using testing::read_text;
using testing::run_cli;
using testing::TempDir;

/// spheres4 with 8 mm voxels (27^3) as NIfTI in `dir`.
void write_head(const TempDir& dir)
{
    io::write_label_image(image::make_phantom("spheres4", {.voxel_mm = 8}).image, dir / "head.nii.gz");
}

TEST(RefineCli, DelaunayOnlyWritesMeshLogPlotAndSummary)
{
    TempDir dir;
    write_head(dir);
    const auto result =
        run_cli("tm-refine", {"--image", (dir / "head.nii.gz").string(), "-o", (dir / "head.msh").string(), "--log",
                              (dir / "log.csv").string(), "--plot", (dir / "log.svg").string(), "--iterations", "5",
                              "--json", (dir / "summary.json").string(), "-q"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const auto summary = read_json(dir / "summary.json");
    EXPECT_EQ(summary["mode"], "delaunay");
    EXPECT_EQ(summary["stop_reason"], "iteration cap");
    EXPECT_LT(summary["total_error_volume_mm3"].get<double>(), summary["start_error_volume_mm3"].get<double>());
    const TetMesh mesh = io::read_tet_mesh(dir / "head.msh");
    EXPECT_EQ(mesh.vertices.size(), summary["nodes"].get<std::size_t>());
    EXPECT_TRUE(volume::check_mesh(mesh).ok());
    // Header and one line per round (the start is round 0).
    std::istringstream csv(read_text(dir / "log.csv"));
    std::size_t lines = 0;
    for (std::string line; std::getline(csv, line);) ++lines;
    EXPECT_EQ(lines, 1u + 6u);
    const std::string svg = read_text(dir / "log.svg");
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    EXPECT_NE(svg.find("<polyline"), std::string::npos);
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
}

TEST(RefineCli, ConstrainedKeepsTheInterfaces)
{
    TempDir dir;
    const LabelImage image = image::make_phantom("junction", {.voxel_mm = 4}).image;
    io::write_label_image(image, dir / "junction.nii.gz");
    const TetMesh start = volume::tetrahedralize(surface::extract_interfaces(image));
    io::write_tet_mesh(start, dir / "junction.msh");
    const auto result =
        run_cli("tm-refine", {"-i", (dir / "junction.msh").string(), "--image", (dir / "junction.nii.gz").string(),
                              "-o", (dir / "finer.msh").string(), "--iterations", "2", "--placement", "longest-edge",
                              "--json", (dir / "summary.json").string(), "-q"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const auto summary = read_json(dir / "summary.json");
    EXPECT_EQ(summary["mode"], "constrained");
    EXPECT_EQ(summary["total_error_volume_mm3"].get<double>(), summary["start_error_volume_mm3"].get<double>());
    const TetMesh finer = io::read_tet_mesh(dir / "finer.msh");
    EXPECT_GT(finer.vertices.size(), start.vertices.size());
    // The rounds keep every interface face; the final improvement may split some at points of the surface (two
    // faces more per split; one per face on the edge beyond two at a junction). The sanitized build splits one
    // here, the release build none.
    ASSERT_TRUE(summary.contains("improvement"));
    const auto splits = summary["improvement"]["nodes_inserted_on_interfaces"].get<std::size_t>();
    EXPECT_GE(finer.faces.size(), start.faces.size());
    EXPECT_LE(finer.faces.size(), start.faces.size() + 4 * splits);
    const auto check = run_cli("tm-check-mesh", {(dir / "finer.msh").string(), "-q"});
    EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
}

TEST(RefineCli, BadPlacementAndMissingImageExitTwoAndLeaveNothing)
{
    TempDir dir;
    write_head(dir);
    const auto bad = run_cli("tm-refine", {"--image", (dir / "head.nii.gz").string(), "-o", (dir / "out.msh").string(),
                                           "--placement", "circumcentre"});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("tm-refine: error: unknown placement \"circumcentre\""), std::string::npos) << bad.err;
    const auto missing =
        run_cli("tm-refine", {"--image", (dir / "none.nii.gz").string(), "-o", (dir / "out.msh").string()});
    EXPECT_EQ(missing.exit_code, 2);
    EXPECT_EQ(dir.files(), std::vector<std::string>{"head.nii.gz"});
}

} // namespace
} // namespace tissuemesh

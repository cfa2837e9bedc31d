// tm-render and tm-report as a user runs them: pictures showing every tissue, the report holding them, and
// bad input refused with exit code 2 and a message, leaving no file behind.
#include <fstream>
#include <gtest/gtest.h>

#include "render/tissue_colours.h"
#include "tests/support/cli.h"
#include "tests/support/pictures.h"

namespace tissuemesh {
namespace {

using testing::read_text;
using testing::run_cli;
using testing::TempDir;

/// Runs `tool` with `args` and the folder's paths; fails the test on a non-zero exit.
void run_ok(const std::string& tool, const std::vector<std::string>& args)
{
    const auto result = run_cli(tool, args);
    ASSERT_EQ(result.exit_code, 0) << tool << ": " << result.err;
}

/// More pixels of a tissue's colour than its legend box (14 x 14 px) could account for.
constexpr std::size_t beyond_legend = 1000;

TEST(RenderCli, SurfaceOfTheSphereHeadShowsAllFourTissues)
{
    TempDir dir;
    run_ok("tm-phantom", {"spheres4", "--voxel-mm", "4", "-o", (dir / "head.nii.gz").string(), "-q"});
    run_ok("tm-extract", {"-i", (dir / "head.nii.gz").string(), "--labels", (dir / "head.labels.json").string(),
                          "--priority", "csf=1", "-o", (dir / "head.ply").string(), "-q"});
    run_ok("tm-render", {"--view", "surface", "-i", (dir / "head.ply").string(), "-o", (dir / "surface.png").string(),
                         "--json", (dir / "surface.json").string(), "-q"});
    const render::Canvas picture = testing::read_png(dir / "surface.png");
    EXPECT_EQ(picture.width(), 800u);
    for (const Label label : std::vector<Label>{1, 2, 3, 4})
        EXPECT_GT(testing::count_shaded(picture, render::tissue_colour(label)), beyond_legend) << "tissue " << label;
    const nlohmann::json summary = testing::read_json(dir / "surface.json");
    EXPECT_EQ(summary["tissues_shown"], nlohmann::json({1, 2, 3, 4}));
    EXPECT_GT(summary["triangles_cut"].get<int>(), 0);

    // Without the cut, only the scalp is seen.
    run_ok("tm-render", {"--view", "surface", "-i", (dir / "head.ply").string(), "-o", (dir / "whole.png").string(),
                         "--cut", "none", "-q"});
    const render::Canvas whole = testing::read_png(dir / "whole.png");
    EXPECT_GT(testing::count_shaded(whole, render::tissue_colour(1)), 50 * beyond_legend);
    EXPECT_LT(testing::count_shaded(whole, render::tissue_colour(4)), beyond_legend);
}

class RenderMeshCli : public ::testing::Test {
protected:
    void SetUp() override
    {
        run_ok("tm-phantom", {"boxes", "--voxel-mm", "4", "-o", (dir / "boxes.nii.gz").string(), "-q"});
        run_ok("tm-extract", {"-i", (dir / "boxes.nii.gz").string(), "--labels", (dir / "boxes.labels.json").string(),
                              "-o", (dir / "boxes.ply").string(), "-q"});
        run_ok("tm-tetra", {"-i", (dir / "boxes.ply").string(), "-o", (dir / "boxes.msh").string(), "--json",
                            (dir / "tetra.json").string(), "-q"});
    }
    TempDir dir;
};

TEST_F(RenderMeshCli, SectionQualityConvergenceAndReport)
{
    run_ok("tm-render",
           {"--view", "section", "-i", (dir / "boxes.msh").string(), "--image", (dir / "boxes.nii.gz").string(), "-o",
            (dir / "section.png").string(), "--axis", "z", "--json", (dir / "render-section.json").string(), "-q"});
    run_ok("tm-render", {"--view", "quality", "-i", (dir / "boxes.msh").string(), "-o", (dir / "quality.png").string(),
                         "--json", (dir / "render-quality.json").string(), "-q"});
    run_ok("tm-refine",
           {"-i", (dir / "boxes.msh").string(), "--image", (dir / "boxes.nii.gz").string(), "-o",
            (dir / "refined.msh").string(), "--log", (dir / "refine.csv").string(), "--iterations", "2", "-q"});
    run_ok("tm-render", {"--view", "convergence", "-i", (dir / "refine.csv").string(), "-o",
                         (dir / "convergence.png").string(), "-q"});

    const render::Canvas section = testing::read_png(dir / "section.png");
    const render::Canvas quality = testing::read_png(dir / "quality.png");
    const nlohmann::json s = testing::read_json(dir / "render-section.json");
    EXPECT_GT(s["tets_cut"].get<int>(), 100);
    for (const Label label : std::vector<Label>{1, 2, 3}) {
        // The cut tets: the tissue colour over the slice of the same tissue, 55% opaque.
        const render::Rgb colour = render::mix(render::mix({255, 255, 255}, render::tissue_colour(label), 0.35),
                                               render::tissue_colour(label), 0.55);
        EXPECT_GT(testing::count_exact(section, colour), beyond_legend) << "tissue " << label;
        EXPECT_GT(testing::count_exact(quality, render::tissue_colour(label)), beyond_legend) << "tissue " << label;
    }
    EXPECT_GT(testing::count_exact(testing::read_png(dir / "convergence.png"), {200, 30, 30}), 100u);

    run_ok("tm-report",
           {"-i", dir.path().string(), "--title", "boxes at 4 mm", "--json", (dir / "report.json").string(), "-q"});
    const std::string html = read_text(dir / "report.html");
    for (const char* tissue : {"cube", "box_a", "box_b"})
        EXPECT_NE(html.find(std::string("<td>") + tissue + "</td>"), std::string::npos) << tissue;
    for (const char* picture : {"section", "quality", "convergence"})
        EXPECT_NE(html.find(std::string("<figcaption>") + picture + "</figcaption>"), std::string::npos) << picture;
    EXPECT_NE(html.find("<td>tm-tetra</td>"), std::string::npos);
    EXPECT_EQ(testing::read_json(dir / "report.json")["pictures"].get<int>(), 3);
}

TEST_F(RenderMeshCli, BadInputExitsTwoWithAMessageAndNoFile)
{
    const std::vector<std::string> before = dir.files();
    auto result = run_cli(
        "tm-render", {"--view", "section", "-i", (dir / "boxes.msh").string(), "-o", (dir / "section.jpg").string()});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("section.jpg: the output must be a .png file"), std::string::npos) << result.err;
    result = run_cli("tm-render", {"--view", "section", "-i", (dir / "boxes.msh").string(), "-o",
                                   (dir / "s.png").string(), "--axis", "x", "--position-mm", "500"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("the plane x = 500 mm misses the mesh"), std::string::npos) << result.err;
    result = run_cli("tm-render",
                     {"--view", "convergence", "-i", (dir / "tetra.json").string(), "-o", (dir / "c.png").string()});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("is this a tm-refine --log CSV?"), std::string::npos) << result.err;
    result =
        run_cli("tm-render", {"--view", "photo", "-i", (dir / "boxes.msh").string(), "-o", (dir / "p.png").string()});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_EQ(dir.files(), before);

    TempDir empty;
    result = run_cli("tm-report", {"-i", empty.path().string()});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("no tool summary"), std::string::npos) << result.err;
    EXPECT_TRUE(empty.files().empty());
}

} // namespace
} // namespace tissuemesh

// tm-render --view field on a real tm-solve result: current between two electrodes on opposite faces of the
// nested cubes; the picture shows the potential falling from the anode to the cathode, and its colour bar
// spans exactly the potential the solver wrote.
#include <fstream>
#include <gtest/gtest.h>

#include "io/read_vtu.h"
#include "io/tet_mesh_io.h"
#include "render/render_field.h"
#include "tests/support/cli.h"
#include "tests/support/pictures.h"
#include "tests/support/programs.h"

namespace tissuemesh {
namespace {

using testing::run_cli;

/// The mean map position (0..1) of the map-coloured pixels in columns [x0, x1) of the picture.
double band_mean(const render::Canvas& picture, std::size_t x0, std::size_t x1)
{
    double sum = 0;
    int n = 0;
    for (std::size_t x = x0; x < x1; ++x)
        for (std::size_t y = 0; y < picture.height(); ++y) {
            const render::Rgb c = picture.at(x, y);
            const double t = render::field_position(c);
            const render::Rgb back = render::field_colour(t);
            if (std::abs(back[0] - c[0]) <= 2 && std::abs(back[1] - c[1]) <= 2 && std::abs(back[2] - c[2]) <= 2)
                sum += t, ++n;
        }
    return n > 0 ? sum / n : -1;
}

TEST(FieldCli, PotentialFallsFromAnodeToCathodeAndTheBarMatchesTheSolution)
{
    testing::TempDir dir;
    io::write_tet_mesh(testing::nested_cubes_mesh(), dir / "cubes.msh");
    std::ofstream(dir / "cond.json") << R"({"1": 0.33, "2": 1.0})";
    // Anode on the x = 0 face, cathode on the x = 4 face (1 mA).
    const auto solve = run_cli("tm-solve", {"-i", (dir / "cubes.msh").string(), "-o", (dir / "solution.vtu").string(),
                                            "--conductivity", (dir / "cond.json").string(), "--electrode",
                                            "0,2,2,1.2,1e-3", "--electrode", "4,2,2,1.2,-1e-3", "-q"});
    ASSERT_EQ(solve.exit_code, 0) << solve.err;
    const auto render = run_cli("tm-render", {"--view", "field", "-i", (dir / "solution.vtu").string(), "-o",
                                              (dir / "potential.png").string(), "--position-mm", "2", "--json",
                                              (dir / "potential.json").string(), "-q"});
    ASSERT_EQ(render.exit_code, 0) << render.err;
    const render::Canvas picture = testing::read_png(dir / "potential.png");
    EXPECT_EQ(picture.width(), 960u);
    const nlohmann::json summary = testing::read_json(dir / "potential.json");
    const io::VtuContent solution = io::read_vtu(dir / "solution.vtu");
    const std::vector<double>& phi = solution.point_array("potential_V")->values;
    EXPECT_EQ(summary["field"], "potential_V");
    EXPECT_EQ(summary["per"], "node");
    EXPECT_EQ(summary["colour_min"].get<double>(), *std::min_element(phi.begin(), phi.end()));
    EXPECT_EQ(summary["colour_max"].get<double>(), *std::max_element(phi.begin(), phi.end()));
    EXPECT_GT(summary["colour_max"].get<double>(), summary["colour_min"].get<double>());
    // The plot is the left 790 px; the cube spans its middle 95% (800 px high fits 4 mm at 190 px/mm, px 15..775).
    const double anode = band_mean(picture, 20, 120), middle = band_mean(picture, 345, 445),
                 cathode = band_mean(picture, 670, 770);
    EXPECT_GT(anode, 0.6) << "high potential next to the anode";
    EXPECT_LT(cathode, 0.4) << "low next to the cathode";
    EXPECT_GT(anode, middle);
    EXPECT_GT(middle, cathode);

    const auto field = run_cli("tm-render", {"--view", "field", "-i", (dir / "solution.vtu").string(), "-o",
                                             (dir / "field.png").string(), "--field", "E", "--clip-percent", "1",
                                             "--json", (dir / "field.json").string(), "-q"});
    ASSERT_EQ(field.exit_code, 0) << field.err;
    const nlohmann::json e = testing::read_json(dir / "field.json");
    EXPECT_EQ(e["field"], "E_magnitude_V_per_m");
    EXPECT_EQ(e["quantity"], "|E|");
    EXPECT_EQ(e["unit"], "V/m");
    EXPECT_EQ(e["per"], "tet");
    EXPECT_LE(e["colour_max"].get<double>(), e["field_max"].get<double>());
    EXPECT_GT(e["colour_max"].get<double>(), e["colour_min"].get<double>());
    EXPECT_GE(e["colour_min"].get<double>(), 0.0);
}

// The Makefile workflow with a solve: the potential and field pictures are made and reach report.html.
TEST(FieldCli, TheWorkflowReportShowsThePotentialAndTheField)
{
    testing::TempDir dir;
    ASSERT_EQ(
        run_cli("tm-phantom", {"boxes", "--voxel-mm", "4", "-o", (dir / "boxes.nii.gz").string(), "-q"}).exit_code, 0);
    std::ofstream(dir / "cond.json") << R"({"1": 0.3, "2": 0.1, "3": 1.0})";
    // Electrodes on the two x faces of the outer box (-24.8 .. 31.2 mm).
    const std::string solve = "SOLVE_ARGS=--conductivity " + (dir / "cond.json").string() +
                              " --electrode -24.8,3,3,8,1e-3 --electrode 31.2,3,3,8,-1e-3";
    const auto result = testing::run_program(
        "make", {"-C", testing::data_path("workflows").string(), "IMAGE=" + (dir / "boxes.nii.gz").string(),
                 "LABELS=" + (dir / "boxes.labels.json").string(), "OUT=" + (dir / "out").string(), "BIN=" TM_TOOLS_DIR,
                 "REMESH_ARGS=--edge-mm 6", "REFINE_ARGS=--iterations 1",
                 "RENDER_POTENTIAL_ARGS=--axis z --position-mm 3", solve, "-j2"});
    ASSERT_EQ(result.exit_code, 0) << result.out << result.err;
    for (const char* step : {"solve", "render-potential", "render-field"})
        EXPECT_EQ(testing::read_json(dir / "out" / (std::string(step) + ".json"))["status"], "ok") << step;
    EXPECT_EQ(testing::read_json(dir / "out" / "render-potential.json")["position_mm"], 3.0);
    std::ifstream in(dir / "out" / "report.html");
    const std::string html{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const std::size_t section = html.find("<figcaption>section</figcaption>"),
                      potential = html.find("<figcaption>potential</figcaption>"),
                      field = html.find("<figcaption>field</figcaption>"),
                      quality = html.find("<figcaption>quality</figcaption>");
    ASSERT_NE(potential, std::string::npos);
    ASSERT_NE(field, std::string::npos);
    EXPECT_LT(section, potential) << "the model and mesh first, then its fields, then the numbers";
    EXPECT_LT(potential, field);
    EXPECT_LT(field, quality);
}

// STOP_AFTER=remesh: the report of a chain stopped at the surfaces holds them and nothing of the mesh steps.
TEST(FieldCli, AReportOfAChainStoppedAfterTheSurfacesShowsThem)
{
    testing::TempDir dir;
    ASSERT_EQ(
        run_cli("tm-phantom", {"boxes", "--voxel-mm", "4", "-o", (dir / "boxes.nii.gz").string(), "-q"}).exit_code, 0);
    const auto make = [&](const std::string& stop) {
        return testing::run_program("make",
                                    {"-C", testing::data_path("workflows").string(),
                                     "IMAGE=" + (dir / "boxes.nii.gz").string(), "OUT=" + (dir / "out").string(),
                                     "BIN=" TM_TOOLS_DIR, "REMESH_ARGS=--edge-mm 6", "STOP_AFTER=" + stop});
    };
    const auto result = make("remesh");
    ASSERT_EQ(result.exit_code, 0) << result.out << result.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / "remeshed.ply"));
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "tetra.json")) << "no mesh step ran";
    std::ifstream in(dir / "out" / "report.html");
    const std::string html{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    EXPECT_NE(html.find("<figcaption>surface</figcaption>"), std::string::npos);
    EXPECT_EQ(html.find("<figcaption>section</figcaption>"), std::string::npos);
    const auto unknown = make("tetra");
    EXPECT_NE(unknown.exit_code, 0);
    EXPECT_NE((unknown.out + unknown.err).find("STOP_AFTER=tetra: only \"remesh\""), std::string::npos) << unknown.err;
}

} // namespace
} // namespace tissuemesh

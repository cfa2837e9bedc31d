// Quality histograms and the convergence plot: counts add up, tissue colours are drawn, the CSV round-trips.
#include <cmath>
#include <fstream>
#include <gtest/gtest.h>

#include "core/error.h"
#include "render/mesh_charts.h"
#include "render/tissue_colours.h"
#include "tests/support/cli.h"
#include "tests/support/pictures.h"
#include "volume/refine_log.h"

namespace tissuemesh {
namespace {

/// Two tets of tissue 4 (one regular, one flat sliver) and one of tissue 9.
TetMesh three_tets()
{
    TetMesh mesh;
    mesh.vertices = {{1, 1, 1},  {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1},     // regular
                     {10, 0, 0}, {12, 0, 0},  {11, 2, 0},  {11, 0.7, 0.05}, // sliver
                     {20, 0, 0}, {21, 0, 0},  {20, 1, 0},  {20, 0, 1}};     // corner tet
    mesh.tets = {{0, 1, 2, 3}, {4, 5, 6, 7}, {8, 9, 10, 11}};
    mesh.tet_labels = {4, 4, 9};
    for (std::size_t t = 0; t < 3; ++t)
        if (signed_volume(mesh, t) < 0) std::swap(mesh.tets[t][2], mesh.tets[t][3]);
    mesh.names = {{4, "brain"}, {9, "bone"}};
    return mesh;
}

TEST(QualityHistograms, CountEveryTetOncePerTissue)
{
    const render::QualityHistograms h = render::quality_histograms(three_tets());
    ASSERT_EQ(h.tissues, (std::vector<Label>{4, 9}));
    std::vector<double> per_tissue(2, 0), per_tissue_ratio(2, 0);
    for (const auto& bin : h.min_dihedral) per_tissue[0] += bin[0], per_tissue[1] += bin[1];
    for (const auto& bin : h.radius_edge) per_tissue_ratio[0] += bin[0], per_tissue_ratio[1] += bin[1];
    EXPECT_EQ(per_tissue, (std::vector<double>{2, 1}));
    EXPECT_EQ(per_tissue_ratio, (std::vector<double>{2, 1}));
    EXPECT_EQ(h.min_dihedral[14][0], 1); // the regular tet: 70.53 deg, bin 70-75
    EXPECT_EQ(h.radius_edge[0][0], 1);   // and radius-edge 0.612, bin 0.6-0.8
    EXPECT_EQ(h.min_dihedral[0][0], 1);  // the sliver: under 5 deg
    EXPECT_LT(h.min_dihedral_deg[0], 5);
    // The corner tet: right angles at the origin's edges, arccos(1/sqrt 3) at the others; R = sqrt(3)/2, shortest edge 1.
    EXPECT_NEAR(h.min_dihedral_deg[1], 54.7356, 1e-3);
    EXPECT_NEAR(h.max_radius_edge_ratio[1], std::sqrt(3.0) / 2, 1e-9);
    EXPECT_EQ(h.tets, (std::vector<std::size_t>{2, 1}));

    const render::Canvas picture = render::render_quality_histograms(three_tets(), h, 900, 400);
    EXPECT_GT(testing::count_exact(picture, render::tissue_colour(4)), 500u);
    EXPECT_GT(testing::count_exact(picture, render::tissue_colour(9)), 500u);
}

TEST(ConvergencePlot, ReadsTheRefineLogAndDrawsBothSeries)
{
    volume::RefineReport report;
    for (std::size_t i = 0; i < 4; ++i) {
        volume::RefineIteration it;
        it.iteration = i, it.nodes = 1000 + 500 * i, it.tets = 5000 + 2500 * i;
        it.total_error_volume_mm3 = 8000.0 / static_cast<double>(1 << (2 * i));
        it.worst_quality_key = 40.0 - 10.0 * static_cast<double>(i), it.seconds = 0.5 * static_cast<double>(i);
        report.iterations.push_back(it);
    }
    testing::TempDir dir;
    std::ofstream(dir / "refine.csv") << volume::refine_log_csv(report);
    const std::vector<render::RefineLogRow> rows = render::read_refine_log(dir / "refine.csv");
    ASSERT_EQ(rows.size(), 4u);
    EXPECT_EQ(rows[3].nodes, 2500);
    EXPECT_DOUBLE_EQ(rows[2].total_error_volume_mm3, 500);
    EXPECT_DOUBLE_EQ(rows[1].worst_quality_key, 30);
    const render::Canvas picture = render::render_convergence(rows);
    EXPECT_GT(testing::count_exact(picture, {200, 30, 30}), 200u); // error volume line
    EXPECT_GT(testing::count_exact(picture, {30, 60, 200}), 200u); // worst key line
}

TEST(ConvergencePlot, RefusesAForeignCsvNamingTheColumn)
{
    testing::TempDir dir;
    std::ofstream(dir / "other.csv") << "x,y\n1,2\n";
    try {
        render::read_refine_log(dir / "other.csv");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(
                      "other.csv: no column \"iteration\" in the header; is this a tm-refine --log CSV?"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_THROW(render::read_refine_log(dir / "missing.csv"), IoError);
}

} // namespace
} // namespace tissuemesh

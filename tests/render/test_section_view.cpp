// The section view of a two-tissue lattice mesh over its image: tissue colours, cut tets, error highlight.
#include <gtest/gtest.h>

#include "core/error.h"
#include "render/render_section.h"
#include "render/tissue_colours.h"
#include "tests/support/pictures.h"

namespace tissuemesh {
namespace {

/// The box [0, 10] mm^3 in 2 mm cubes of 6 Kuhn tets each (1 500 tets); tissue 1 where x < 5, else 2.
TetMesh lattice_mesh()
{
    TetMesh mesh;
    const int n = 5;
    auto id = [&](int i, int j, int k) { return static_cast<std::uint32_t>(i + (n + 1) * (j + (n + 1) * k)); };
    for (int k = 0; k <= n; ++k)
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) mesh.vertices.push_back({2.0 * i, 2.0 * j, 2.0 * k});
    const int axes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                for (const auto& order : axes) {
                    std::array<int, 3> c{i, j, k};
                    Tet tet{id(i, j, k), 0, 0, id(i + 1, j + 1, k + 1)};
                    for (int step = 0; step < 2; ++step) {
                        ++c[static_cast<std::size_t>(order[step])];
                        tet[static_cast<std::size_t>(step + 1)] = id(c[0], c[1], c[2]);
                    }
                    mesh.tets.push_back(tet);
                    if (signed_volume(mesh, mesh.tets.size() - 1) < 0)
                        std::swap(mesh.tets.back()[2], mesh.tets.back()[3]);
                    mesh.tet_labels.push_back(i < 2 ? 1 : 2);
                }
    mesh.names = {{1, "left"}, {2, "right"}};
    return mesh;
}

/// 1 mm voxels with centres at 0.5 .. 9.5 mm: tissue 1 where x < 4, else 2 (the mesh's boundary is at 4 mm).
LabelImage lattice_image()
{
    LabelImage image({10, 10, 10}, {1, 1, 1}, {0.5, 0.5, 0.5});
    for (std::size_t k = 0; k < 10; ++k)
        for (std::size_t j = 0; j < 10; ++j)
            for (std::size_t i = 0; i < 10; ++i) image.at(i, j, k) = i < 4 ? 1 : 2;
    return image;
}

render::Rgb over_slice(Label label, double opacity)
{
    return render::mix(render::mix({255, 255, 255}, render::tissue_colour(label), 0.35), render::tissue_colour(label),
                       opacity);
}

TEST(SectionView, ShowsEveryTissueOverItsSlice)
{
    const TetMesh mesh = lattice_mesh();
    const LabelImage image = lattice_image();
    render::SectionViewReport report;
    const render::Canvas picture =
        render::render_section(mesh, &image, nullptr, {.width_px = 300, .height_px = 300, .legend = false}, &report);
    EXPECT_DOUBLE_EQ(report.position_mm, 5.0);
    // z = 5 mm cuts the middle layer of cubes: every one of its 25 cubes has 6 tets across the plane.
    EXPECT_EQ(report.tets_cut, 150u);
    EXPECT_EQ(report.tets_highlighted, 0u);
    EXPECT_GT(testing::count_exact(picture, over_slice(1, 0.55)), 5000u);
    EXPECT_GT(testing::count_exact(picture, over_slice(2, 0.55)), 10000u);
    EXPECT_GT(testing::count_exact(picture, {70, 70, 70}), 1000u); // the element edges
}

TEST(SectionView, HighlightsTetsWithErrorVolume)
{
    const TetMesh mesh = lattice_mesh();
    const LabelImage image = lattice_image();
    std::vector<double> error(mesh.tets.size(), 0.0);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        if (mesh.tet_labels[t] == 2) error[t] = 1.0; // one voxel (1 mm^3) each
    render::SectionViewReport report;
    const render::Canvas picture =
        render::render_section(mesh, &image, &error, {.width_px = 300, .height_px = 300, .legend = false}, &report);
    EXPECT_EQ(report.tets_highlighted, 90u); // 3 of the 5 columns of cubes are tissue 2
    EXPECT_EQ(testing::count_exact(picture, over_slice(2, 0.55)), 0u);
    EXPECT_GT(testing::count_exact(picture, over_slice(1, 0.55)), 5000u);
    const render::Rgb red_over_slice =
        render::mix(render::mix({255, 255, 255}, render::tissue_colour(2), 0.35), render::error_colour, 0.85);
    EXPECT_GT(testing::count_exact(picture, red_over_slice), 10000u);
    // Below the threshold (2 voxels), nothing is highlighted.
    render::render_section(mesh, &image, &error, {.width_px = 300, .height_px = 300, .min_error_voxels = 2}, &report);
    EXPECT_EQ(report.tets_highlighted, 0u);
}

TEST(SectionView, RefusesAPlaneOutsideTheMesh)
{
    const TetMesh mesh = lattice_mesh();
    try {
        render::render_section(mesh, nullptr, nullptr, {.axis = 0, .at_centre = false, .position_mm = 20});
        FAIL();
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "section view: the plane x = 20 mm misses the mesh (0 .. 10 mm)");
    }
    const std::vector<double> short_error(3, 0.0);
    EXPECT_THROW(render::render_section(mesh, nullptr, &short_error), InputError);
}

} // namespace
} // namespace tissuemesh

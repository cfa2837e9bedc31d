// The parts of the snakes: field sampling in world mm, enclosed regions, start surfaces, separation of nested
// snakes, curvature-adapted resolution, and refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "core/error.h"
#include "image/phantom.h"
#include "surface/check_complex.h"
#include "surface/detail/triangle_distance.h"
#include "surface/snake.h"

namespace tissuemesh {
namespace {

constexpr double pi = 3.14159265358979323846;

/// A grid with anisotropic spacing, a rotated direction and an origin, like the ellipsoids phantom.
LabelImage rotated_grid()
{
    const double c = std::cos(0.4), s = std::sin(0.4);
    return LabelImage({12, 10, 8}, {1.0, 1.5, 2.0}, {-5, 3, 7}, {c, -s, 0, s, c, 0, 0, 0, 1});
}

TEST(SnakeField, TrilinearSamplingReproducesLinearFieldsInWorldMm)
{
    const LabelImage grid = rotated_grid();
    const Vec3 a{0.3, -0.7, 0.2};
    const auto linear = [&](const Vec3& p) { return dot(a, p) + 1.5; };
    std::vector<float> values(grid.voxel_count());
    for (std::size_t k = 0; k < 8; ++k)
        for (std::size_t j = 0; j < 10; ++j)
            for (std::size_t i = 0; i < 12; ++i)
                values[grid.linear_index(i, j, k)] =
                    static_cast<float>(linear(grid.index_to_world({double(i), double(j), double(k)})));
    const surface::PotentialField field(grid, values);
    for (const Vec3& index : {Vec3{3.25, 4.5, 2.75}, Vec3{0.1, 8.9, 6.5}, Vec3{10.99, 0.01, 0.5}}) {
        const Vec3 p = grid.index_to_world(index);
        EXPECT_NEAR(field.value(p), linear(p), 1e-5); // float storage
        const Vec3 g = field.gradient(p);
        for (std::size_t d = 0; d < 3; ++d) EXPECT_NEAR(g[d], a[d], 1e-5);
        const Vec3 back = field.world_to_index(field.index_to_world(index));
        for (std::size_t d = 0; d < 3; ++d) EXPECT_NEAR(back[d], index[d], 1e-12);
    }
}

TEST(SnakeField, EnclosedRegionHoldsTheTissueAndWhatItSurrounds)
{
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = 4.0});
    const std::map<Label, std::size_t> counts = count_labels(phantom.image);
    const std::vector<char> skull = surface::enclosed_region(phantom.image, 2);
    std::size_t inside = 0;
    for (const char c : skull) inside += c != 0;
    // At 4 mm the one-voxel CSF may be broken, but the skull shell (6 mm) is closed: skull, CSF and brain.
    EXPECT_EQ(inside, counts.at(2) + counts.at(3) + counts.at(4));
    try {
        surface::enclosed_region(phantom.image, 9);
        FAIL() << "no throw";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("has no voxel of tissue 9"), std::string::npos) << e.what();
    }
}

TEST(SnakeField, SmoothedIndicatorCrossesHalfAtTheBoundary)
{
    // A half space x > 0 on a 1 mm grid whose voxel faces lie at half-integer x: the blurred indicator is
    // symmetric about the face, so its zero level stays on it whatever the sigma.
    LabelImage image({20, 4, 4}, {1, 1, 1}, {-9.5, 0, 0});
    for (std::size_t k = 0; k < 4; ++k)
        for (std::size_t j = 0; j < 4; ++j)
            for (std::size_t i = 10; i < 20; ++i) image.at(i, j, k) = 1;
    std::vector<char> region(image.voxel_count());
    for (std::size_t v = 0; v < region.size(); ++v) region[v] = image.labels()[v] == 1;
    const surface::PotentialField field = surface::label_potential(image, region, 1.5);
    EXPECT_NEAR(field.value({0.0, 1.5, 1.5}), 0.0, 1e-6);
    EXPECT_GT(field.value({0.5, 1.5, 1.5}), 0.0);
    EXPECT_LT(field.value({-0.5, 1.5, 1.5}), 0.0);
    EXPECT_NEAR(field.value({8.0, 1.5, 1.5}), 0.5, 1e-4);
}

TEST(SnakeSurfaces, EllipsoidIsClosedOnItsEllipsoidWithEdgesNearTheTarget)
{
    const Vec3 centre{1, -2, 3}, radii{30, 20, 10};
    const InterfaceComplex e = surface::ellipsoid_surface(centre, radii, 3.0, {5, 0});
    const surface::CheckReport check = surface::check_complex(e);
    ASSERT_TRUE(check.ok()) << (check.first_error() ? check.first_error()->description : "");
    for (const Vec3& p : e.vertices) {
        const Vec3 q = p - centre;
        EXPECT_NEAR(q[0] * q[0] / 900 + q[1] * q[1] / 400 + q[2] * q[2] / 100, 1.0, 1e-9);
    }
    EXPECT_NEAR(check.tissues.at(5).volume_mm3, 4.0 / 3.0 * pi * 30 * 20 * 10, 0.02 * 4.0 / 3.0 * pi * 6000);
    double longest = 0;
    for (const Triangle& t : e.triangles) longest = std::max(longest, distance(e.vertices[t[0]], e.vertices[t[1]]));
    EXPECT_LT(longest, 1.3 * 3.0 * 1.3);
}

/// Two snakes whose fields ask for the same sphere: the inner one, grown by its field, must stop at the
/// separation from the outer one instead of crossing it.
TEST(SnakeSeparation, InnerSnakeStopsShortOfTheOuterOne)
{
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = 6.0});
    const surface::PotentialField scalp =
        surface::label_potential(phantom.image, surface::enclosed_region(phantom.image, 1), 6.0);
    const std::vector<surface::SnakeTarget> targets{{{1, 0}, scalp}, {{2, 1}, scalp}};
    InterfaceComplex complex = surface::ellipsoid_surface({0, 0, 0}, {100, 100, 100}, 8.0, {1, 0});
    surface::append_complex(complex, surface::ellipsoid_surface({0, 0, 0}, {70, 70, 70}, 8.0, {2, 1}));
    const surface::SnakeReport report =
        surface::evolve_snakes(complex, targets, {.min_separation_voxels = 0.5, .max_iterations = 25});
    EXPECT_GT(report.moves, 0u);
    const surface::CheckReport check = surface::check_complex(complex);
    ASSERT_TRUE(check.ok()) << (check.first_error() ? check.first_error()->description : "");
    // Closest approach of the two surfaces, vertex to triangle: at least the separation (3 mm).
    double closest = 1e300, inner_max_radius = 0;
    for (std::size_t t = 0; t < complex.triangle_count(); ++t) {
        if (!(complex.sides[t] == LabelPair{1, 0})) continue;
        const Triangle& f = complex.triangles[t];
        const surface::detail::TriangleCorners c{complex.vertices[f[0]], complex.vertices[f[1]],
                                                 complex.vertices[f[2]]};
        for (std::size_t u = 0; u < complex.triangle_count(); ++u)
            if (complex.sides[u] == LabelPair{2, 1})
                for (const std::uint32_t v : complex.triangles[u]) {
                    closest =
                        std::min(closest, distance(complex.vertices[v],
                                                   surface::detail::closest_point_on_triangle(complex.vertices[v], c)));
                    inner_max_radius = std::max(inner_max_radius, norm(complex.vertices[v]));
                }
    }
    EXPECT_GE(closest, 3.0 - 1e-9);
    EXPECT_GT(report.refused_moves, 0u);
    EXPECT_GT(inner_max_radius, 80.0); // it did grow towards the scalp
}

TEST(SnakeResolution, CurvatureShortensEdgesWhereTheSurfaceBends)
{
    // The rotated ellipsoids phantom's outer tissue: strongly curved at the ends of its long axis.
    const image::Phantom phantom = image::make_phantom("ellipsoids", {.voxel_mm = 3.0});
    const std::vector<surface::SnakeTarget> targets = surface::nested_label_targets(phantom.image, {1}, 3.0);
    InterfaceComplex uniform = surface::bounding_ellipsoids(targets, 1.15, 10.0);
    InterfaceComplex adapted = uniform;
    const surface::SnakeReport a = surface::evolve_snakes(uniform, targets, {.target_edge_mm = 10.0});
    const surface::SnakeReport b =
        surface::evolve_snakes(adapted, targets, {.target_edge_mm = 10.0, .max_chord_error_mm = 0.3});
    std::cout << "[ figures  ] ellipsoids 3 mm, 10 mm edges: " << a.triangles << " triangles uniform, " << b.triangles
              << " with a 0.3 mm chord bound\n";
    EXPECT_GT(b.triangles, a.triangles);
    EXPECT_TRUE(surface::check_complex(adapted).ok());
}

TEST(SnakeErrors, OptionsAndLabelsAreChecked)
{
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = 8.0});
    const std::vector<surface::SnakeTarget> targets = surface::nested_label_targets(phantom.image, {1}, 8.0);
    InterfaceComplex start = surface::ellipsoid_surface({0, 0, 0}, {100, 100, 100}, 16.0, {1, 0});
    const auto message = [&](InterfaceComplex complex, const surface::SnakeOptions& options) -> std::string {
        try {
            surface::evolve_snakes(complex, targets, options);
        } catch (const InputError& e) {
            return e.what();
        }
        return "no error";
    };
    EXPECT_NE(message(start, {.tension = 1.5}).find("must lie in [0, 1]"), std::string::npos);
    EXPECT_NE(message(start, {.max_iterations = 0}).find("iteration cap"), std::string::npos);
    InterfaceComplex wrong = start;
    for (LabelPair& side : wrong.sides) side = {3, 0};
    EXPECT_NE(message(wrong, {}).find("which no snake stands for"), std::string::npos);
    InterfaceComplex open = start;
    open.triangles.pop_back();
    open.sides.pop_back();
    EXPECT_NE(message(open, {}).find("not fit for tetrahedralization"), std::string::npos);
    EXPECT_THROW(surface::nested_label_targets(phantom.image, {1, 1}, 8.0), InputError);
    EXPECT_THROW(surface::ellipsoid_surface({0, 0, 0}, {1, 0, 1}, 1.0, {1, 0}), InputError);
}

} // namespace
} // namespace tissuemesh

// The wedge rule: triangles sharing one vertex may not be edited into lying on each other. Its angle is
// checked on configurations whose answer is known in closed form, and the rule on the chain that once broke
// (the thin phantom's shell at 1 mm, remeshed to 2 mm edges, where TetGen then made a flat tetrahedron).
#include <gtest/gtest.h>

#include <cmath>

#include "image/phantom.h"
#include "surface/check_complex.h"
#include "surface/decimate.h"
#include "surface/detail/wedge_angle.h"
#include "surface/extract_interfaces.h"
#include "surface/remesh.h"
#include "surface/smooth.h"
#include "volume/check_mesh.h"
#include "volume/tetrahedralize.h"

namespace tissuemesh::surface {
namespace {

constexpr double pi = 3.14159265358979323846;
const Vec3 origin{0, 0, 0};

TEST(WedgeAngle, FoldedTriangleOpensByItsElevation)
{
    // The second triangle's corners lie in the first one's sector, 0.01 above its plane at distances
    // 1/sqrt(2) and sqrt(2) from the apex: the farther corner is the flatter one, so the two triangles are
    // closest (as seen from the apex) along it: the opening is atan(0.01 / sqrt(2)).
    const double t = 0.01;
    const double opening = detail::wedge_angle_deg(origin, {1, 0, 0}, {0, 1, 0}, {0.5, 0.5, t}, {1, 1, t});
    EXPECT_NEAR(opening, std::atan(t / std::sqrt(2.0)) * 180 / pi, 1e-9);
}

TEST(WedgeAngle, OppositeTrianglesOfAFlatFanAreWide)
{
    // Triangles opposite each other across the centre of a flat fan (b = -a exactly) lie on one great circle,
    // 90 degrees apart along it. Regression: the crossing test took the zero vector (the planes' normals are
    // equal, so their cross product vanishes) for a common point and answered 0.
    EXPECT_NEAR(detail::wedge_angle_deg(origin, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}), 90, 1e-9);
    EXPECT_NEAR(
        detail::wedge_angle_deg(origin, {0.3, -0.4, 0.1}, {0.2, 0.5, -0.3}, {-0.3, 0.4, -0.1}, {-0.2, -0.5, 0.3}),
        180 - std::acos((0.3 * 0.2 - 0.4 * 0.5 - 0.1 * 0.3) / std::sqrt(0.26 * 0.38)) * 180 / pi, 1e-9);
}

TEST(WedgeAngle, CertainlyOpenOnlyWhenTheAngleSaysSo)
{
    // The shortcut may say "open" only where the angle is at least the limit; on clear cases it must say it.
    const Triangle a{0, 1, 2}, b{0, 3, 4};
    std::uint64_t state = 12345;
    const auto next = [&] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return static_cast<double>(state >> 11) / 9007199254740992.0 * 2 - 1;
    };
    int open = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        const detail::TriangleCorners ca{origin, Vec3{next(), next(), next()}, Vec3{next(), next(), next()}};
        // Half the trials: the second triangle near the first one's plane, where wedges are thin.
        const double lift = trial % 2 ? 0.02 : 1.0;
        const detail::TriangleCorners cb{origin, Vec3{next(), next(), lift * next()},
                                         Vec3{next(), next(), lift * next()}};
        for (const double limit : {1.0, 10.0}) {
            if (!detail::wedge_certainly_open(a, ca, b, cb, limit)) continue;
            ++open;
            EXPECT_GE(*detail::wedge_between(a, ca, b, cb), limit) << trial;
        }
    }
    EXPECT_GT(open, 10000);
    const auto at = [](double deg) { return Vec3{std::cos(deg * pi / 180), std::sin(deg * pi / 180), 0}; };
    EXPECT_TRUE(detail::wedge_certainly_open(a, {origin, at(0), at(60)}, b, {origin, at(120), at(180)}, 1.0));
    EXPECT_TRUE(detail::wedge_certainly_open(a, {origin, at(0), at(60)}, b, {origin, at(180), at(240)}, 1.0));
    EXPECT_FALSE(detail::wedge_certainly_open(a, {origin, at(0), at(60)}, b, {origin, at(60.5), at(120)}, 1.0));
}

TEST(WedgeAngle, FlatFanNeighboursTwoApartAreWide)
{
    // A flat fan of six 60-degree triangles: the first and the third share only the centre and stand 60
    // degrees apart along the circle, although both lie in one plane.
    const auto at = [](double deg) { return Vec3{std::cos(deg * pi / 180), std::sin(deg * pi / 180), 0}; };
    EXPECT_NEAR(detail::wedge_angle_deg(origin, at(0), at(60), at(120), at(180)), 60, 1e-9);
    EXPECT_NEAR(detail::wedge_angle_deg(origin, at(0), at(60), at(180), at(240)), 120, 1e-9);
}

TEST(WedgeAngle, CrossingTrianglesHaveNoOpening)
{
    // The second triangle pierces the first one's sector: they overlap along a segment from the apex.
    EXPECT_EQ(detail::wedge_angle_deg(origin, {1, 0, 0}, {0, 1, 0}, {1, 1, 1}, {1, 1, -1}), 0);
}

TEST(WedgeAngle, OnlyTrianglesSharingExactlyOneVertexHaveAWedge)
{
    const detail::TriangleCorners a{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}};
    const detail::TriangleCorners b{Vec3{0, 0, 0}, Vec3{1, 1, 0.01}, Vec3{0.5, 0.5, 0.01}};
    EXPECT_TRUE(detail::wedge_between({0, 1, 2}, a, {0, 3, 4}, b).has_value());
    EXPECT_FALSE(detail::wedge_between({0, 1, 2}, a, {0, 1, 4}, b).has_value()); // an edge
    EXPECT_FALSE(detail::wedge_between({0, 1, 2}, a, {5, 3, 4}, b).has_value()); // nothing
    EXPECT_NEAR(*detail::wedge_between({0, 1, 2}, a, {0, 3, 4}, b), std::atan(0.01 / std::sqrt(2.0)) * 180 / pi, 1e-9);
}

/// Smallest opening between triangles of `complex` that share exactly one vertex.
double thinnest_wedge_deg(const InterfaceComplex& complex)
{
    std::vector<std::vector<std::uint32_t>> star(complex.vertices.size());
    for (std::uint32_t t = 0; t < complex.triangles.size(); ++t)
        for (const std::uint32_t v : complex.triangles[t]) star[v].push_back(t);
    const auto corners = [&](std::uint32_t t) {
        const Triangle& tri = complex.triangles[t];
        return detail::TriangleCorners{complex.vertices[tri[0]], complex.vertices[tri[1]], complex.vertices[tri[2]]};
    };
    double thinnest = 180;
    for (const auto& around : star)
        for (std::size_t i = 0; i < around.size(); ++i)
            for (std::size_t j = i + 1; j < around.size(); ++j)
                if (const auto w = detail::wedge_between(complex.triangles[around[i]], corners(around[i]),
                                                         complex.triangles[around[j]], corners(around[j])))
                    thinnest = std::min(thinnest, *w);
    return thinnest;
}

/// Regression: the thin phantom's one-voxel shell at 1 mm (no priority, so it breaks into pieces and the
/// tissues on both sides meet at junction vertices) through smooth -> decimate 0.5 mm -> remesh 2 mm. The
/// remesher once put an edge of the outer surface 1.5e-14 mm above a triangle of the inner surface, both
/// sharing a junction vertex (opening 6e-13 degrees); tm-check-surface passed it and TetGen made a flat
/// tetrahedron there, which tm-tetra refused. Now no edit may open a wedge under 1 degree.
TEST(WedgeRule, ThinShellChainStaysOpenAndTetrahedralizes)
{
    const image::Phantom phantom = image::make_phantom("thin", {.voxel_mm = 1});
    InterfaceComplex complex = extract_interfaces(phantom.image);
    smooth(complex, phantom.image);
    decimate(complex, {.max_distance_mm = 0.5});
    remesh(complex, {.target_edge_mm = 2});
    ASSERT_TRUE(check_complex(complex).ok());
    EXPECT_GE(thinnest_wedge_deg(complex), 1.0 - 1e-9);
    const TetMesh mesh = volume::tetrahedralize(complex);
    EXPECT_TRUE(volume::check_mesh(mesh).ok());
}

} // namespace
} // namespace tissuemesh::surface

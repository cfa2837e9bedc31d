// repair(): crossing and touching surfaces moved apart locally, with the topology kept; a thin layer gets
// its thickness back; a crossing too deep for the rounds allowed fails with the place.
#include <gtest/gtest.h>

#include <iostream>

#include "core/error.h"
#include "image/phantom.h"
#include "surface/check_complex.h"
#include "surface/detail/triangle_distance.h"
#include "surface/extract_interfaces.h"
#include "surface/repair.h"
#include "tests/support/complexes.h"

namespace tissuemesh {
namespace {

/// A layer (tissue 1) between a ball (2, radius r_inner) and the outside (0, beyond r_outer): two icospheres.
InterfaceComplex layered_ball(int levels, double r_outer, double r_inner)
{
    InterfaceComplex complex = testing::icosphere(levels, r_outer, {0, 0, 0});
    const InterfaceComplex inner = testing::icosphere(levels, r_inner, {0, 0, 0});
    const auto base = static_cast<std::uint32_t>(complex.vertices.size());
    complex.vertices.insert(complex.vertices.end(), inner.vertices.begin(), inner.vertices.end());
    for (const Triangle& t : inner.triangles) complex.add_triangle({base + t[0], base + t[1], base + t[2]}, {2, 1});
    return complex;
}

/// Smallest distance from a vertex of one patch to a triangle of the other (brute force; small complexes).
double layer_thickness(const InterfaceComplex& complex)
{
    double thinnest = 1e300;
    for (std::size_t t = 0; t < complex.triangles.size(); ++t) {
        if (complex.sides[t].from != 1) continue; // the outer surface, 1|0
        const Triangle& tri = complex.triangles[t];
        const surface::detail::TriangleCorners c{complex.vertices[tri[0]], complex.vertices[tri[1]],
                                                 complex.vertices[tri[2]]};
        for (std::size_t s = 0; s < complex.triangles.size(); ++s)
            if (complex.sides[s].from == 2)
                for (const std::uint32_t v : complex.triangles[s])
                    thinnest = std::min(thinnest,
                                        distance(complex.vertices[v],
                                                 surface::detail::closest_point_on_triangle(complex.vertices[v], c)));
    }
    return thinnest;
}

/// Pushes the inner-surface vertices within `reach_mm` of `towards` radially out to `radius_mm`.
void bulge_inner(InterfaceComplex& complex, const Vec3& towards, double reach_mm, double radius_mm)
{
    std::vector<char> inner(complex.vertices.size(), 0);
    for (std::size_t t = 0; t < complex.triangles.size(); ++t)
        if (complex.sides[t].from == 2)
            for (const std::uint32_t v : complex.triangles[t]) inner[v] = 1;
    for (std::size_t v = 0; v < complex.vertices.size(); ++v)
        if (inner[v] && distance(complex.vertices[v], towards) < reach_mm)
            complex.vertices[v] = (radius_mm / norm(complex.vertices[v])) * complex.vertices[v];
}

void expect_fit(const InterfaceComplex& complex)
{
    const surface::CheckReport check = surface::check_complex(complex);
    EXPECT_TRUE(check.ok()) << (check.first_error() ? check.first_error()->description : "");
}

TEST(RepairContacts, CrossingLayerSurfacesAreMovedApart)
{
    InterfaceComplex complex = layered_ball(3, 20.0, 19.0);
    bulge_inner(complex, {0, 0, 19}, 4.0, 20.6); // the ball pokes through its 1 mm layer
    const surface::CheckReport broken = surface::check_complex(complex);
    ASSERT_GT(broken.count(surface::DefectKind::patch_intersection), 0u);
    const surface::RepairReport report = surface::repair(complex, {.gap_mm = 0.1});
    std::cout << "[ figures  ] bulge through a 1 mm layer: " << report.patch_intersections_before << " crossing pairs, "
              << report.near_contacts_before << " near-contacts; " << report.moved_vertices
              << " vertices moved (at most " << report.max_move_mm << " mm) in " << report.rounds
              << " rounds; layer thickness now " << layer_thickness(complex) << " mm\n";
    expect_fit(complex);
    EXPECT_GT(report.patch_intersections_before, 0u);
    EXPECT_GT(report.moved_vertices, 0u);
    EXPECT_EQ(report.near_contacts_after, 0u);
    EXPECT_GE(layer_thickness(complex), 0.1) << "the layer keeps the gap";
    // Local: only vertices near the bulge moved, and the outer surface still encloses about the same volume.
    EXPECT_LT(report.moved_vertices, complex.vertices.size() / 4);
    const surface::CheckReport after = surface::check_complex(complex);
    EXPECT_EQ(after.tissues.at(1).components, 2u) << "the layer: outer and inner surface";
    EXPECT_EQ(after.tissues.at(2).components, 1u);
    ASSERT_FALSE(report.actions.empty());
    EXPECT_EQ(report.actions.front().kind, surface::RepairKind::intersection);
    EXPECT_NE(report.actions.front().description.find("moved apart crossing 1|0 and 2|1 triangles near ("),
              std::string::npos)
        << report.actions.front().description;
    EXPECT_EQ(report.actions.front().tissues, (std::vector<Label>{0, 1, 2}));
}

TEST(RepairContacts, NearContactsArePushedToTheGap)
{
    InterfaceComplex complex = layered_ball(3, 20.0, 19.0);
    bulge_inner(complex, {19, 0, 0}, 3.0, 19.95); // 0.05 mm from the outer surface, no crossing
    ASSERT_TRUE(surface::check_complex(complex).ok());
    ASSERT_LT(layer_thickness(complex), 0.1);
    const surface::RepairReport report = surface::repair(complex, {.gap_mm = 0.2});
    std::cout << "[ figures  ] layer pinched to 0.05 mm: " << report.near_contacts_before << " near-contacts -> "
              << report.near_contacts_after << ", " << report.moved_vertices << " vertices moved; thickness now "
              << layer_thickness(complex) << " mm\n";
    expect_fit(complex);
    EXPECT_GT(report.near_contacts_before, 0u);
    EXPECT_EQ(report.near_contacts_after, 0u);
    EXPECT_GE(layer_thickness(complex), 0.2 * 0.99);
    ASSERT_FALSE(report.actions.empty());
    EXPECT_EQ(report.actions.front().kind, surface::RepairKind::near_contact);
}

TEST(RepairContacts, FoldThroughItselfIsSmoothedOut)
{
    // One vertex dragged past a neighbour: its triangles fold over the patch beyond that neighbour.
    InterfaceComplex complex = testing::icosphere(3, 10.0, {0, 0, 0});
    const std::uint32_t v = complex.triangles[0][0], u = complex.triangles[0][1];
    complex.vertices[v] = complex.vertices[u] + 0.7 * (complex.vertices[u] - complex.vertices[v]);
    const surface::CheckReport broken = surface::check_complex(complex);
    ASSERT_GT(broken.count(surface::DefectKind::self_intersection), 0u);
    const surface::RepairReport report = surface::repair(complex);
    std::cout << "[ figures  ] fold: " << report.self_intersections_before << " self-intersecting pairs; "
              << report.moved_vertices << " vertices moved in " << report.rounds << " rounds\n";
    expect_fit(complex);
    EXPECT_GT(report.self_intersections_before, 0u);
}

TEST(RepairContacts, ImageKeepsMovedVerticesNearTheirVoxels)
{
    const image::Phantom phantom = image::make_phantom("thin", {.voxel_mm = 2.0});
    InterfaceComplex complex = surface::extract_interfaces(phantom.image);
    ASSERT_TRUE(surface::check_complex(complex).ok());
    const surface::RepairReport untouched = surface::repair(complex, {.gap_mm = 0.1}, &phantom.image);
    EXPECT_FALSE(untouched.changed()) << "a valid extraction has nothing to repair";
    // Push the ball-surface vertices within 2 mm of one of them 1.5 voxels outward, through the one-voxel shell.
    Vec3 centre{0, 0, 0};
    for (const Vec3& p : complex.vertices) centre = centre + p;
    centre = (1.0 / static_cast<double>(complex.vertices.size())) * centre;
    std::vector<char> ball(complex.vertices.size(), 0);
    for (std::size_t t = 0; t < complex.triangles.size(); ++t)
        if (complex.sides[t].from + complex.sides[t].to == 3) // the 1|2 patch
            for (const std::uint32_t v : complex.triangles[t]) ball[v] = 1;
    const auto seed = static_cast<std::size_t>(std::find(ball.begin(), ball.end(), 1) - ball.begin());
    const Vec3 around = complex.vertices[seed];
    for (std::size_t v = 0; v < complex.vertices.size(); ++v) {
        if (!ball[v] || distance(complex.vertices[v], around) > 2.0) continue;
        const Vec3 out = complex.vertices[v] - centre;
        complex.vertices[v] = complex.vertices[v] + (3.0 / norm(out)) * out;
    }
    ASSERT_GT(surface::check_complex(complex).count(surface::DefectKind::patch_intersection), 0u);
    const surface::RepairReport report = surface::repair(complex, {}, &phantom.image);
    std::cout << "[ figures  ] thin 2 mm, ball vertices pushed 1.5 voxels through the shell: "
              << report.patch_intersections_before << " crossing pairs; " << report.moved_vertices
              << " vertices moved (at most " << report.max_move_mm << " mm) in " << report.rounds << " rounds\n";
    expect_fit(complex);
    EXPECT_GT(report.moved_vertices, 0u);
}

TEST(RepairContacts, DeepCrossingFailsWithThePlace)
{
    InterfaceComplex complex = layered_ball(2, 20.0, 19.0);
    bulge_inner(complex, {0, 0, 19}, 8.0, 23.0);
    try {
        surface::repair(complex, {.max_rounds = 1});
        FAIL() << "one round cannot undo a 4 mm crossing";
    } catch (const AlgorithmError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("intersecting triangle pairs remain after 1 rounds of local moves, first between "),
                  std::string::npos)
            << message;
        EXPECT_NE(message.find(") mm; the surfaces cross over more than local moves can undo"), std::string::npos)
            << message;
    }
}

} // namespace
} // namespace tissuemesh

// The order of the triangles around a junction edge: fan_order() on its own, the checker's
// tangled-junction defect, and the editor refusing to turn a flat pocket inside out (the usc19-5 failure).
#include <gtest/gtest.h>

#include "surface/check_complex.h"
#include "surface/detail/cgal_intersections.h"
#include "surface/detail/complex_editor.h"
#include "surface/detail/edge_fan.h"

namespace tissuemesh {
namespace {

using surface::detail::ComplexEditor;
using surface::detail::fan_order;
using surface::detail::FanBlade;
using surface::detail::FanOrder;

// Three patches around the edge from (0,0,0) to (0,0,1): blades towards +x, +y and -x-y. The right-hand
// turn about +z goes +x -> +y -> -x-y. Tissue 1 lies between +x and +y, 2 between +y and -x-y, 3 between
// -x-y and +x.
const Vec3 a{0, 0, 0}, b{0, 0, 1};

TEST(EdgeFan, ThreePatchesInOrder)
{
    // Forward blades have the tissue ahead of the turn in front (`to`).
    const std::vector<FanBlade> blades{
        {{1, 0, 0.5}, {3, 1}, true}, {{0, 1, 0.5}, {1, 2}, true}, {{-1, -1, 0.5}, {2, 3}, true}};
    EXPECT_EQ(fan_order(a, b, blades), FanOrder::in_order);
    // The same triangles listed backwards along the edge (from b to a): nothing changes.
    std::vector<FanBlade> reversed = blades;
    for (FanBlade& blade : reversed) blade.forward = false;
    for (FanBlade& blade : reversed) std::swap(blade.side.from, blade.side.to);
    EXPECT_EQ(fan_order(a, b, reversed), FanOrder::in_order);
    // Any blade first.
    EXPECT_EQ(fan_order(a, b, std::vector<FanBlade>{blades[2], blades[0], blades[1]}), FanOrder::in_order);
}

TEST(EdgeFan, SwappedBladesAreOutOfOrder)
{
    // The +y blade moved past -x-y (to -y): tissue 2 now lies on both sides of the -x-y blade.
    const std::vector<FanBlade> blades{
        {{1, 0, 0.5}, {3, 1}, true}, {{0.2, -1, 0.5}, {1, 2}, true}, {{-1, -1, 0.5}, {2, 3}, true}};
    EXPECT_EQ(fan_order(a, b, blades), FanOrder::out_of_order);
}

TEST(EdgeFan, CoincidentOrFlatBladesOverlap)
{
    const std::vector<FanBlade> same{
        {{1, 0, 0.5}, {3, 1}, true}, {{0, 1, 0.5}, {1, 2}, true}, {{2, 0, 0.9}, {2, 3}, true}};
    EXPECT_EQ(fan_order(a, b, same), FanOrder::overlapping);
    const std::vector<FanBlade> flat{
        {{1, 0, 0.5}, {3, 1}, true}, {{0, 1, 0.5}, {1, 2}, true}, {{0, 0, 3}, {2, 3}, true}};
    EXPECT_EQ(fan_order(a, b, flat), FanOrder::overlapping);
    // Opposite blades (at pi from each other) are fine.
    const std::vector<FanBlade> opposite{
        {{1, 0, 0.5}, {3, 1}, true}, {{0, 1, 0.5}, {1, 2}, true}, {{-1, 0, 0.5}, {2, 3}, true}};
    EXPECT_EQ(fan_order(a, b, opposite), FanOrder::in_order);
}

TEST(EdgeFan, DecidedExactlyWhenBladesAreNearlyCoplanar)
{
    // Two blades 1e-200 apart in angle: floating point cannot tell their order, the exact predicate can.
    EXPECT_EQ(surface::detail::orientation(a, b, {1, 0, 0}, {1, 1e-200, 0}), 1);
    EXPECT_EQ(surface::detail::orientation(a, b, {1, 0, 0}, {1, -1e-200, 0}), -1);
    EXPECT_EQ(surface::detail::orientation(a, b, {1, 0, 0}, {2, 0, 7}), 0);
    const std::vector<FanBlade> thin{
        {{1, 0, 0.5}, {3, 1}, true}, {{1, 1e-200, 0.5}, {1, 2}, true}, {{-1, -1, 0.5}, {2, 3}, true}};
    EXPECT_EQ(fan_order(a, b, thin), FanOrder::in_order);
    const std::vector<FanBlade> crossed{
        {{1, 0, 0.5}, {3, 1}, true}, {{1, -1e-200, 0.5}, {1, 2}, true}, {{-1, -1, 0.5}, {2, 3}, true}};
    EXPECT_EQ(fan_order(a, b, crossed), FanOrder::out_of_order);
}

/// Two tetrahedra on one face ABC (in z = 0): tissue 1 above it, apex D at height `d_height` (a flat
/// pocket when small), tissue 2 below, apex E at z = -3; air (0) around. AB, BC and CA are junction edges.
InterfaceComplex two_pockets(double d_height)
{
    InterfaceComplex complex;
    complex.names = {{0, "air"}, {1, "one"}, {2, "two"}};
    complex.vertices = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {1.3, 1.3, d_height}, {1.3, 1.3, -3}};
    const std::uint32_t A = 0, B = 1, C = 2, D = 3, E = 4;
    complex.add_triangle({A, B, C}, {2, 1}); // normal +z: from two (below) into one (above)
    for (const Triangle& t : {Triangle{A, B, D}, Triangle{B, C, D}, Triangle{C, A, D}}) complex.add_triangle(t, {1, 0});
    for (const Triangle& t : {Triangle{B, A, E}, Triangle{C, B, E}, Triangle{A, C, E}}) complex.add_triangle(t, {2, 0});
    return complex;
}

TEST(EdgeFan, CheckerFindsAPocketTurnedInsideOut)
{
    const surface::CheckReport fit = surface::check_complex(two_pockets(0.3));
    EXPECT_TRUE(fit.ok()) << (fit.first_error() ? fit.first_error()->description : "");
    EXPECT_EQ(fit.junction_edges, 3u);
    // D below ABC, inside tissue 2's tetrahedron: no triangle meets another, but around AB, BC and CA the
    // triangles now turn in an order that puts tissue 1 on both sides of ABC.
    const surface::CheckReport inverted = surface::check_complex(two_pockets(-0.3));
    EXPECT_EQ(inverted.count(surface::DefectKind::patch_intersection), 0u);
    EXPECT_EQ(inverted.count(surface::DefectKind::self_intersection), 0u);
    EXPECT_EQ(inverted.count(surface::DefectKind::tangled_junction), 3u);
    bool named = false;
    for (const surface::Defect& defect : inverted.defects)
        if (defect.kind == surface::DefectKind::tangled_junction)
            named = named || (defect.description.find("tangled junction edge") != std::string::npos &&
                              defect.tissues == std::vector<Label>{0, 1, 2} && defect.triangles.size() == 3);
    EXPECT_TRUE(named);
    EXPECT_NE(surface::repair_hint(inverted).find("re-extract"), std::string::npos);
}

TEST(EdgeFan, EditorRefusesToTurnAFlatPocketInsideOut)
{
    // Moving D from 0.3 above ABC to 0.3 below tilts its triangles by 26 degrees only and crosses nothing:
    // only the order around the junction edges tells.
    const Vec3 through{1.3, 1.3, -0.3}, up{1.3, 1.3, 0.6};
    {
        ComplexEditor editor(two_pockets(0.3), {}, 1.0);
        EXPECT_FALSE(editor.try_move(3, through));
        EXPECT_EQ(editor.counters().wedge, 1u);
        EXPECT_TRUE(editor.try_move(3, up));
        EXPECT_TRUE(surface::check_complex(editor.result()).ok());
    }
    {
        ComplexEditor editor(two_pockets(0.3), {}, 1.0);
        // In a batch the moves of every triangle around the edge go back together (E's too).
        EXPECT_EQ(editor.move_together({3, 4}, {through, {1.3, 1.3, -3.5}}), (std::vector<char>{0, 0}));
        EXPECT_EQ(editor.move_together({3, 4}, {up, {1.3, 1.3, -3.5}}), (std::vector<char>{1, 1}));
        EXPECT_TRUE(surface::check_complex(editor.result()).ok());
    }
}

} // namespace
} // namespace tissuemesh

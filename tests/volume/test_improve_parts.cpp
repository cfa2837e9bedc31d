// The mesh improver's parts: the shape measure and its gradient, the smallest vector of a hull, the journal
// of WorkMesh, and the flips on small meshes built in code.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>

#include "core/error.h"
#include "volume/check_mesh.h"
#include "volume/detail/flips.h"
#include "volume/detail/interface_flip.h"
#include "volume/detail/smooth_node.h"
#include "volume/detail/surface_reference.h"
#include "volume/detail/tet_quality.h"
#include "volume/detail/work_mesh.h"
#include "volume/tetrahedralize.h"
#include "tests/support/complexes.h"

namespace tissuemesh::volume::detail {
namespace {

TEST(ImproveQuality, RegularTetHasTheSineOfSeventyDegreesEverywhere)
{
    const TetCorners regular{Vec3{1, 1, 1}, Vec3{1, -1, -1}, Vec3{-1, 1, -1}, Vec3{-1, -1, 1}};
    // The corners are in negative order: the sines carry the sign of the volume.
    const double expected = std::sqrt(8.0) / 3;
    for (const double s : dihedral_sines(regular)) EXPECT_NEAR(s, -expected, 1e-12);
    const TetCorners positive_order{regular[0], regular[2], regular[1], regular[3]};
    EXPECT_NEAR(min_sine(positive_order), expected, 1e-12);
    EXPECT_NEAR(min_dihedral_deg(positive_order), 70.528779, 1e-5);
    EXPECT_TRUE(positive(positive_order[0], positive_order[1], positive_order[2], positive_order[3]));
    EXPECT_FALSE(positive(regular[0], regular[1], regular[2], regular[3]));
}

TEST(ImproveQuality, GradientsMatchFiniteDifferences)
{
    // A few irregular tets, slivers among them; central differences with a step far below their edges.
    const std::vector<TetCorners> tets{
        {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0.2, 1, 0}, Vec3{0.3, 0.3, 0.8}},
        {Vec3{0, 0, 0}, Vec3{2, 0, 0.1}, Vec3{2, 2, 0}, Vec3{0, 2, 0.1}}, // a sliver: four nearly coplanar corners
        {Vec3{1, 2, 3}, Vec3{4, 2, 3.5}, Vec3{2, 5, 3}, Vec3{2.5, 3, 0.2}},
    };
    const double h = 1e-6;
    for (const TetCorners& tet : tets) {
        const std::array<double, 6> sines = dihedral_sines(tet);
        for (int k = 0; k < 4; ++k) {
            const std::array<Vec3, 6> g = dihedral_sine_gradients(tet, k, sines);
            for (int axis = 0; axis < 3; ++axis) {
                TetCorners plus = tet, minus = tet;
                plus[k][axis] += h, minus[k][axis] -= h;
                const std::array<double, 6> up = dihedral_sines(plus), down = dihedral_sines(minus);
                for (int e = 0; e < 6; ++e)
                    EXPECT_NEAR(g[e][axis], (up[e] - down[e]) / (2 * h), 1e-6) << "corner " << k << " edge " << e;
            }
        }
    }
}

TEST(ImproveQuality, MinNormPointOfAHull)
{
    EXPECT_EQ(min_norm_point({{1, 2, 3}}), (Vec3{1, 2, 3}));
    // Two points on either side of the x axis: the segment's nearest point lies on the axis.
    const Vec3 d = min_norm_point({{1, 1, 0}, {1, -1, 0}});
    EXPECT_NEAR(d[0], 1, 1e-12);
    EXPECT_NEAR(d[1], 0, 1e-12);
    // A triangle around the origin in its plane: the origin itself, hence no ascent direction.
    EXPECT_EQ(min_norm_point({{1, 0, 0}, {-1, 1, 0}, {-1, -1, 0}}), (Vec3{0, 0, 0}));
    // A triangle above the origin: its nearest point is the foot of the perpendicular.
    const Vec3 up = min_norm_point({{1, 0, 1}, {-1, 1, 1}, {-1, -1, 1}});
    EXPECT_NEAR(up[0], 0, 1e-12);
    EXPECT_NEAR(up[1], 0, 1e-12);
    EXPECT_NEAR(up[2], 1, 1e-12);
}

/// Tissue 1 in a 10 mm cube around tissue 2 in a 4 mm cube, meshed by TetGen without improvement.
TetMesh nested_boxes()
{
    InterfaceComplex complex;
    testing::add_box(complex, {0, 0, 0}, {10, 10, 10}, 1, 0);
    testing::add_box(complex, {3, 3, 3}, {7, 7, 7}, 2, 1);
    return tetrahedralize(complex, {.improve = false});
}

bool same_mesh(const TetMesh& a, const TetMesh& b)
{
    return a.vertices == b.vertices && a.tets == b.tets && a.tet_labels == b.tet_labels && a.faces == b.faces &&
           a.face_sides == b.face_sides;
}

TEST(ImproveWorkMesh, RollbackRestoresTheMeshExactly)
{
    const TetMesh mesh = nested_boxes();
    WorkMesh work(mesh);
    const TetMesh start = work.result();
    const std::size_t mark = work.mark();
    // Every kind of edit: flips wherever they improve, a node moved, a node added and faces replaced.
    std::size_t flips = 0;
    for (std::uint32_t t = 0; t < work.tet_slots(); ++t) {
        if (!work.alive(t)) continue;
        const Tet tet = work.tet(t);
        for (const auto& e : edge_corners) flips += remove_edge(work, tet[e[0]], tet[e[1]]);
    }
    EXPECT_GT(flips, 0u);
    work.move_node(0, work.point(0) + Vec3{0.1, 0, 0});
    const std::uint32_t v = work.add_node({5, 5, 5});
    work.add_face({0, 1, v}, {1, 0}, true);
    EXPECT_FALSE(same_mesh(work.result(), start));
    work.rollback(mark);
    EXPECT_TRUE(same_mesh(work.result(), start));
}

TEST(ImproveWorkMesh, SweptFacesAreTheStarBeforeAndAfter)
{
    const TetMesh mesh = nested_boxes();
    WorkMesh work(mesh);
    std::vector<std::array<Vec3, 3>> before, after;
    // A node inside the inner box's face z = 3 (not on its edges) slides within it.
    std::uint32_t v = 0;
    while (v < work.node_count() && !(work.kind(v) == NodeKind::surface && work.point(v)[2] == 3 &&
                                      work.tissues_at(v) == std::vector<Label>{1, 2}))
        ++v;
    ASSERT_LT(v, work.node_count()) << "no node inside the inner box's bottom face";
    const std::size_t mark = work.mark();
    const Vec3 from = work.point(v), to = from + Vec3{0.01, 0.01, 0};
    work.move_node(v, to);
    work.swept_faces(mark, before, after);
    ASSERT_EQ(before.size(), work.faces_of(v).size());
    ASSERT_EQ(after.size(), before.size());
    const auto holds = [](const std::vector<std::array<Vec3, 3>>& faces, const Vec3& p) {
        return std::all_of(faces.begin(), faces.end(),
                           [&](const std::array<Vec3, 3>& c) { return std::find(c.begin(), c.end(), p) != c.end(); });
    };
    EXPECT_TRUE(holds(before, from));
    EXPECT_TRUE(holds(after, to));
    work.rollback(mark);
    // Undone, nothing is swept.
    work.swept_faces(work.mark(), before, after);
    EXPECT_TRUE(before.empty() && after.empty());
    // A node on a junction curve sweeps the faces of every patch at it: two cubes of tissues 1 and 2 side by side,
    // whose shared square meets the outer faces along a curve.
    testing::VoxelBlock block{.nx = 2, .ny = 1, .nz = 1};
    block.labels = {1, 2};
    WorkMesh cubes(tetrahedralize(testing::voxel_faces(block), {.improve = false}));
    std::uint32_t c = 0;
    while (c < cubes.node_count() && cubes.kind(c) != NodeKind::curve) ++c;
    ASSERT_LT(c, cubes.node_count());
    cubes.move_node(c, cubes.point(c) + Vec3{0, 0.01, 0});
    cubes.swept_faces(0, before, after);
    EXPECT_EQ(before.size(), cubes.faces_of(c).size());
    EXPECT_EQ(after.size(), cubes.faces_of(c).size());
}

TEST(ImproveWorkMesh, KindsFollowTheConstraintFaces)
{
    // Two unit cubes of tissues 1 and 2 side by side: the square they share meets the outer faces along a
    // junction curve of four edges; the other cube corners lie on one patch each.
    testing::VoxelBlock block{.nx = 2, .ny = 1, .nz = 1};
    block.labels = {1, 2};
    WorkMesh work(tetrahedralize(testing::voxel_faces(block), {.improve = false}));
    std::size_t corners = 0, curves = 0, surfaces = 0;
    for (std::uint32_t v = 0; v < work.node_count(); ++v) {
        const NodeKind kind = work.kind(v);
        corners += kind == NodeKind::corner, curves += kind == NodeKind::curve, surfaces += kind == NodeKind::surface;
        if (kind == NodeKind::curve) {
            EXPECT_EQ(work.curve_neighbours(v).size(), 2u);
            EXPECT_EQ(work.tissues_at(v), (std::vector<Label>{0, 1, 2}));
        }
    }
    EXPECT_EQ(corners, 0u);
    EXPECT_EQ(curves, 4u);
    EXPECT_EQ(surfaces, 8u);
}

TEST(ImproveWorkMesh, NonConformingMeshesAreRefused)
{
    TetMesh mesh;
    mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}, {0.3, 0.3, 1}};
    mesh.tets = {{0, 1, 2, 3}, {0, 2, 1, 4}, {0, 1, 2, 5}};
    mesh.tet_labels = {1, 1, 1};
    EXPECT_THROW(WorkMesh{mesh}, InputError);
}

/// Three tets around the edge from (0,0,-h) to (0,0,h) through the triangle of radius r in z = 0 (or, with
/// `two`, the two tets on that triangle), positively oriented.
TetMesh bipyramid(double r, double h, bool two)
{
    TetMesh mesh;
    mesh.vertices = {{0, 0, -h}, {0, 0, h}};
    for (int k = 0; k < 3; ++k) mesh.vertices.push_back({r * std::cos(2.0944 * k), r * std::sin(2.0944 * k), 0});
    mesh.tets =
        two ? std::vector<Tet>{{0, 2, 3, 4}, {1, 2, 4, 3}} : std::vector<Tet>{{0, 1, 2, 3}, {0, 1, 3, 4}, {0, 1, 4, 2}};
    mesh.tet_labels.assign(mesh.tets.size(), 1);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        if (signed_volume(mesh, t) < 0) std::swap(mesh.tets[t][2], mesh.tets[t][3]);
    return mesh;
}

double worst(const TetMesh& mesh)
{
    double q = 1;
    for (const Tet& t : mesh.tets)
        q = std::min(q, min_sine({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], mesh.vertices[t[3]]}));
    return q;
}

TEST(ImproveFlips, ThreeTwoAndTwoThreeFlipsWhereTheyPay)
{
    // A long edge through a small triangle: its three tets (smallest sine 0.32) become two (0.89).
    WorkMesh tall(bipyramid(1, 3, false));
    ASSERT_TRUE(remove_edge(tall, 0, 1));
    EXPECT_EQ(tall.result().tets.size(), 2u);
    EXPECT_NEAR(worst(tall.result()), 0.888, 1e-3);
    // A wide triangle between close apexes: its two tets (0.55) become three around the new edge (0.87).
    WorkMesh wide(bipyramid(3, 1, true));
    ASSERT_TRUE(remove_faces(wide, 0, 0));
    EXPECT_EQ(wide.result().tets.size(), 3u);
    EXPECT_NEAR(worst(wide.result()), 0.866, 1e-3);
    // The other way round neither pays, so neither is made.
    WorkMesh good_three(bipyramid(3, 1, false));
    EXPECT_FALSE(remove_edge(good_three, 0, 1));
    WorkMesh good_two(bipyramid(1, 3, true));
    EXPECT_FALSE(remove_faces(good_two, 0, 0));
    EXPECT_EQ(good_two.result().tets.size(), 2u);
}

TEST(ImproveFlips, NoFlipRemovesAConstraintFace)
{
    // The wide pair again, its shared triangle now an interface between tissues 1 and 2: no 2-3 flip.
    TetMesh mesh = bipyramid(3, 1, true);
    mesh.tet_labels = {1, 2};
    mesh.faces = {{2, 3, 4}};
    mesh.face_sides = {{1, 2}};
    WorkMesh work(mesh);
    EXPECT_FALSE(remove_faces(work, 0, 0));
    EXPECT_FALSE(remove_faces(work, 1, 0));
}

/// A flat tet of tissue 1 filling a shallow crease of the interface with tissue 2 (a valley along ab, 2 atan(h)
/// deep: 13.7 degrees for h = 0.12), tissue 1 above it up to e and tissue 2 below down to f: what the 1 mm head's thin
/// grey matter and CSF left as their worst tets (all four nodes on the interface).
TetMesh crease(double h)
{
    TetMesh mesh;
    mesh.vertices = {{-1, 0, 0}, {1, 0, 0}, {0, -1, h}, {0, 1, h}, {0, 0, 2}, {0, 0, -2}};
    mesh.tets = {{0, 1, 2, 3}, {0, 2, 3, 4}, {1, 2, 3, 4}, {0, 1, 2, 5}, {0, 1, 3, 5}};
    mesh.tet_labels = {1, 1, 1, 2, 2};
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        if (signed_volume(mesh, t) < 0) std::swap(mesh.tets[t][2], mesh.tets[t][3]);
    // The interface (a, b, c) and (a, d, b), normals from tissue 1 (above) into 2.
    mesh.faces = {{0, 1, 2}, {0, 3, 1}};
    mesh.face_sides = {{1, 2}, {1, 2}};
    return mesh;
}

TEST(ImproveFlips, AFlatTetOnACreasedInterfaceGoesToTheOtherSide)
{
    const double h = 0.12;
    const TetMesh mesh = crease(h);
    const SurfaceReference reference(mesh.vertices, mesh.faces, mesh.face_sides);
    WorkMesh work(mesh);
    ASSERT_NEAR(min_dihedral_deg(work.corners(0)), 9.67, 0.01); // and 166.3 degrees at ab
    // The new faces (a, c, d) and (b, d, c) lie up to h off the old ones: refused within a tighter tolerance.
    EXPECT_FALSE(flip_interface_edge(work, 0, 1, reference, 0.5 * h));
    ASSERT_TRUE(flip_interface_edge(work, 0, 1, reference, 1.5 * h));
    const TetMesh flipped = work.result();
    const MeshCheckReport check = check_mesh(flipped);
    EXPECT_TRUE(check.ok()) << (check.problems.empty() ? "" : check.problems.front());
    // The flat tet went: tissue 1 keeps its two tets above, tissue 2 has two new ones on edge cd.
    ASSERT_EQ(flipped.tets.size(), 4u);
    std::size_t in_two = 0;
    for (std::size_t t = 0; t < flipped.tets.size(); ++t) {
        EXPECT_GT(signed_volume(flipped, t), 0);
        in_two += flipped.tet_labels[t] == 2;
    }
    EXPECT_EQ(in_two, 2u);
    EXPECT_GT(worst(flipped), sine_of_deg(30));
    // The interface is now (a, c, d) and (b, d, c), turned from tissue 1 into 2 (downwards).
    ASSERT_EQ(flipped.faces.size(), 2u);
    for (std::size_t f = 0; f < 2; ++f) {
        const Triangle& t = flipped.faces[f];
        const Vec3 n =
            cross(flipped.vertices[t[1]] - flipped.vertices[t[0]], flipped.vertices[t[2]] - flipped.vertices[t[0]]);
        EXPECT_TRUE(std::find(t.begin(), t.end(), 2u) != t.end() && std::find(t.begin(), t.end(), 3u) != t.end());
        EXPECT_LT(flipped.face_sides[f].from == 1 ? n[2] : -n[2], 0);
    }
}

TEST(ImproveFlips, AFlatTetThatLinksTwoPartsOfItsTissueStays)
{
    // Tissue 1 above the flat tet in two tets, (a, c, d, e1) and (b, c, d, e2), with a tet of tissue 3 between them:
    // the flat tet is all that joins them, so the flip would break tissue 1 in two.
    TetMesh mesh = crease(0.12);
    mesh.vertices[4] = {-0.5, 0, 2};
    mesh.vertices.push_back({0.5, 0, 2});
    mesh.tets[2] = {1, 2, 3, 6};
    mesh.tets.push_back({2, 3, 4, 6});
    mesh.tet_labels.push_back(3);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        if (signed_volume(mesh, t) < 0) std::swap(mesh.tets[t][2], mesh.tets[t][3]);
    const MeshCheckReport check = check_mesh(mesh); // a triangulation (its 1|3 faces are not listed)
    ASSERT_EQ(check.inverted_tets + check.flat_tets + check.nonconforming_faces, 0u);
    const SurfaceReference reference(mesh.vertices, mesh.faces, mesh.face_sides);
    WorkMesh work(mesh);
    EXPECT_FALSE(flip_interface_edge(work, 0, 1, reference, 1));
    EXPECT_EQ(work.result().tets.size(), mesh.tets.size());
}

TEST(ImproveFlips, AFlatTetWhoseOtherFacesAreInterfacesStays)
{
    // Tissue 3 above the flat tet: (a, c, d) and (b, c, d) are interfaces already, so the flip would leave tissue 2
    // on both sides of them.
    TetMesh mesh = crease(0.12);
    mesh.tet_labels = {1, 3, 3, 2, 2};
    const SurfaceReference reference(mesh.vertices, mesh.faces, mesh.face_sides);
    WorkMesh work(mesh);
    EXPECT_FALSE(flip_interface_edge(work, 0, 1, reference, 1));
}

} // namespace
} // namespace tissuemesh::volume::detail

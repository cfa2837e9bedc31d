#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <gtest/gtest.h>

#include "core/error.h"
#include "volume/tetrahedralize.h"

namespace tissuemesh::volume {
namespace {

/// Builds complexes from axis-aligned box faces, sharing vertices by exact coordinates.
class BoxComplex {
public:
    InterfaceComplex complex;

    /// Adds the faces of box [lo, hi] with tissue `inside` behind them; `outside(face)` gives the tissue in
    /// front of each face (0..5: -x, +x, -y, +y, -z, +z); a face whose outside is `skip` is left out.
    void add_box(const Vec3& lo, const Vec3& hi, Label inside, const std::array<Label, 6>& outside, Label skip = 65535)
    {
        auto v = [&](int i, int j, int k) { return vertex({i ? hi[0] : lo[0], j ? hi[1] : lo[1], k ? hi[2] : lo[2]}); };
        // Corners of each face counter-clockwise seen from outside (normal outward).
        const int faces[6][4][3] = {
            {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}},
            {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},
            {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
        for (int f = 0; f < 6; ++f) {
            if (outside[f] == skip) continue;
            std::array<std::uint32_t, 4> q;
            for (int c = 0; c < 4; ++c) q[c] = v(faces[f][c][0], faces[f][c][1], faces[f][c][2]);
            complex.add_triangle({q[0], q[1], q[2]}, {inside, outside[f]});
            complex.add_triangle({q[0], q[2], q[3]}, {inside, outside[f]});
        }
    }
    /// Adds the faces of box [lo, hi] reversed: `outside` behind, `inside` in front (a cavity wall seen from outside).
    void add_box_reversed(const Vec3& lo, const Vec3& hi, Label inside, Label outside)
    {
        const std::size_t first = complex.triangles.size();
        add_box(lo, hi, inside, {outside, outside, outside, outside, outside, outside});
        for (std::size_t t = first; t < complex.triangles.size(); ++t) {
            std::swap(complex.triangles[t][1], complex.triangles[t][2]);
            complex.sides[t] = {complex.sides[t].to, complex.sides[t].from};
        }
    }

private:
    std::map<Vec3, std::uint32_t> index_;
    std::uint32_t vertex(const Vec3& p)
    {
        const auto [it, inserted] = index_.emplace(p, static_cast<std::uint32_t>(complex.vertices.size()));
        if (inserted) complex.vertices.push_back(p);
        return it->second;
    }
};

std::map<Label, double> volumes_by_tissue(const TetMesh& mesh)
{
    std::map<Label, double> volumes;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) volumes[mesh.tet_labels[t]] += signed_volume(mesh, t);
    return volumes;
}

/// Two nested boxes: tissue 1 (10 mm cube) around tissue 2 (4 mm cube), background 0 outside.
InterfaceComplex nested_boxes()
{
    BoxComplex boxes;
    boxes.add_box({0, 0, 0}, {10, 10, 10}, 1, {0, 0, 0, 0, 0, 0});
    boxes.add_box({3, 3, 3}, {7, 7, 7}, 2, {1, 1, 1, 1, 1, 1});
    return boxes.complex;
}

TEST(Tetrahedralize, NestedBoxesGetExactTissueVolumesAndPositiveTets)
{
    TetrahedralizeReport report;
    const TetMesh mesh = tetrahedralize(nested_boxes(), {}, {}, &report);
    ASSERT_GT(mesh.tets.size(), 0u);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) ASSERT_GT(signed_volume(mesh, t), 0) << "tet " << t;
    const auto volumes = volumes_by_tissue(mesh);
    // Boxes are represented exactly by flat facets: volumes agree to round-off.
    EXPECT_NEAR(volumes.at(1), 1000.0 - 64.0, 1e-9);
    EXPECT_NEAR(volumes.at(2), 64.0, 1e-9);
    EXPECT_EQ(volumes.count(0), 0u) << "the background outside the object must not be meshed";
    EXPECT_EQ(report.tets, mesh.tets.size());
    EXPECT_EQ(report.split_interface_triangles, 0u) << "-Y keeps every input triangle whole here";
}

TEST(Tetrahedralize, PreservedInterfacesAreTetFacesWithTheirTissues)
{
    const InterfaceComplex complex = nested_boxes();
    const TetMesh mesh = tetrahedralize(complex, {.preserve_interfaces = true});
    // With -Y every input triangle is an output face, unchanged, with the same tissue pair.
    std::set<std::pair<std::array<Vec3, 3>, std::pair<Label, Label>>> input;
    auto key = [](std::array<Vec3, 3> corners) {
        std::sort(corners.begin(), corners.end());
        return corners;
    };
    for (std::size_t t = 0; t < complex.triangles.size(); ++t) {
        const Triangle& tri = complex.triangles[t];
        input.insert({key({complex.vertices[tri[0]], complex.vertices[tri[1]], complex.vertices[tri[2]]}),
                      {complex.sides[t].from, complex.sides[t].to}});
    }
    std::set<std::pair<std::array<Vec3, 3>, std::pair<Label, Label>>> output;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const Triangle& tri = mesh.faces[f];
        output.insert({key({mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]}),
                       {mesh.face_sides[f].from, mesh.face_sides[f].to}});
    }
    EXPECT_EQ(input, output);
    // Each interface face is a face of a tet of each of its tissues, on the right side of it.
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const Triangle& tri = mesh.faces[f];
        const std::set<std::uint32_t> corners(tri.begin(), tri.end());
        const Vec3 normal =
            cross(mesh.vertices[tri[1]] - mesh.vertices[tri[0]], mesh.vertices[tri[2]] - mesh.vertices[tri[0]]);
        int behind = 0, in_front = 0;
        for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
            int shared = 0, apex = -1;
            for (const std::uint32_t v : mesh.tets[t]) corners.count(v) ? ++shared : apex = static_cast<int>(v);
            if (shared != 3) continue;
            const bool front = dot(mesh.vertices[apex] - mesh.vertices[tri[0]], normal) > 0;
            const Label expected = front ? mesh.face_sides[f].to : mesh.face_sides[f].from;
            EXPECT_EQ(mesh.tet_labels[t], expected) << "face " << f;
            front ? ++in_front : ++behind;
        }
        EXPECT_EQ(behind, 1) << "face " << f;
        EXPECT_EQ(in_front, mesh.face_sides[f].to == 0 ? 0 : 1) << "face " << f;
    }
}

TEST(Tetrahedralize, BoxesSideBySideShareTheirJunction)
{
    // Tissues 1 and 2 touch along x = 5; background 0, 1 and 2 meet along the square's edges.
    BoxComplex boxes;
    boxes.add_box({0, 0, 0}, {5, 5, 5}, 1, {0, 2, 0, 0, 0, 0});
    boxes.add_box({5, 0, 0}, {10, 5, 5}, 2, {1, 0, 0, 0, 0, 0}, /*skip=*/1);
    const TetMesh mesh = tetrahedralize(boxes.complex);
    const auto volumes = volumes_by_tissue(mesh);
    EXPECT_NEAR(volumes.at(1), 125.0, 1e-9);
    EXPECT_NEAR(volumes.at(2), 125.0, 1e-9);
}

TEST(Tetrahedralize, BackgroundCavityIsMeshedOrDropped)
{
    // A 10 mm cube of tissue 1 with a 4 mm cavity of background inside.
    BoxComplex boxes;
    boxes.add_box({0, 0, 0}, {10, 10, 10}, 1, {0, 0, 0, 0, 0, 0});
    // The cavity wall: normals point into the cavity (from tissue 1 into background 0).
    boxes.add_box_reversed({3, 3, 3}, {7, 7, 7}, 0, 1);
    const auto kept = volumes_by_tissue(tetrahedralize(boxes.complex, {.mesh_background_cavities = true}));
    EXPECT_NEAR(kept.at(1), 936.0, 1e-9);
    EXPECT_NEAR(kept.at(0), 64.0, 1e-9);
    const auto dropped = volumes_by_tissue(tetrahedralize(boxes.complex, {.mesh_background_cavities = false}));
    EXPECT_NEAR(dropped.at(1), 936.0, 1e-9);
    EXPECT_EQ(dropped.count(0), 0u);
}

TEST(Tetrahedralize, PerTissueVolumeBoundHoldsInThatTissueOnly)
{
    // Without -Y: TetGen 1.5 refuses every point that encroaches a preserved interface triangle, and in a
    // 4 mm box every circumcentre does, so the bound could not be met there with -Y.
    TetrahedralizeOptions options;
    options.preserve_interfaces = false;
    options.max_volume_per_tissue_mm3 = {{2, 0.5}};
    const TetMesh mesh = tetrahedralize(nested_boxes(), options);
    double largest_inner = 0, largest_outer = 0;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        (mesh.tet_labels[t] == 2 ? largest_inner : largest_outer) =
            std::max(mesh.tet_labels[t] == 2 ? largest_inner : largest_outer, signed_volume(mesh, t));
    EXPECT_LE(largest_inner, 0.5 * (1 + 1e-9));
    EXPECT_GT(largest_outer, 0.5) << "the bound must not spread to the other tissue";
}

/// The largest tet volume of `tissue` among tets whose centroid lies in the box [low, high].
double largest_tet_in(const TetMesh& mesh, Label tissue, const Vec3& low, const Vec3& high)
{
    double largest = 0;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        if (mesh.tet_labels[t] != tissue) continue;
        Vec3 centroid{0, 0, 0};
        for (const std::uint32_t v : mesh.tets[t]) centroid = centroid + 0.25 * mesh.vertices[v];
        bool inside = true;
        for (int a = 0; a < 3; ++a) inside = inside && centroid[a] > low[a] && centroid[a] < high[a];
        if (inside) largest = std::max(largest, signed_volume(mesh, t));
    }
    return largest;
}

/// Meshes `complex` with at most 0.5 mm^3 per tet of `tissue`, as TetGen bounds them: without -Y (with it, the
/// triangles of small boxes would refuse the refinement, as above) and without the improver (its moves enlarged
/// tets past the bound, 7 tets to 0.58 mm^3 in the hollow box below, until it was given the bounds too; the test is
/// of TetGen's regions). Expects the tets of `tissue` in each of
/// its `pieces` (regions [low, high]) to hold the bound, none over it, and the tissue's exact `volume_mm3`.
TetMesh expect_bound_in_every_piece(const InterfaceComplex& complex, Label tissue,
                                    const std::vector<std::pair<Vec3, Vec3>>& pieces, double volume_mm3)
{
    const double bound_mm3 = 0.5;
    TetrahedralizeReport report;
    const TetMesh mesh = tetrahedralize(
        complex, {.preserve_interfaces = false, .max_volume_per_tissue_mm3 = {{tissue, bound_mm3}}, .improve = false},
        {}, &report);
    for (const auto& [low, high] : pieces) {
        const double largest = largest_tet_in(mesh, tissue, low, high);
        EXPECT_GT(largest, 0.0) << "no tet of tissue " << tissue << " in the piece from " << low[0] << " mm";
        EXPECT_LE(largest, bound_mm3 * (1 + 1e-9)) << "the piece from " << low[0] << " mm lacks the bound";
    }
    EXPECT_EQ(report.tets_over_volume_bound, 0u);
    EXPECT_NEAR(volumes_by_tissue(mesh).at(tissue), volume_mm3, 1e-9);
    return mesh;
}

// Issue 32: region_seeds made one seed per tissue, so a tissue in two pieces had its volume bound (TetGen -a per
// region) in one piece only, and the warning then blamed the interface triangles.
TEST(Tetrahedralize, TissueInTwoPiecesHasItsVolumeBoundInBothPieces)
{
    // Two 4 mm boxes of tissue 2, apart, in a box of tissue 1.
    BoxComplex boxes;
    boxes.add_box({0, 0, 0}, {20, 10, 10}, 1, {0, 0, 0, 0, 0, 0});
    boxes.add_box({3, 3, 3}, {7, 7, 7}, 2, {1, 1, 1, 1, 1, 1});
    boxes.add_box({13, 3, 3}, {17, 7, 7}, 2, {1, 1, 1, 1, 1, 1});
    expect_bound_in_every_piece(boxes.complex, 2, {{{3, 3, 3}, {7, 7, 7}}, {{13, 3, 3}, {17, 7, 7}}}, 128.0);
}

// The nested case of the same finding: tissue 1 as a hollow box (two shells: its outside and its cavity wall)
// with tissue 2 in the cavity, and a second piece of tissue 1 inside tissue 2.
TEST(Tetrahedralize, TissueInAHollowPieceAndAnIslandInItsCavityHasItsBoundInBoth)
{
    BoxComplex boxes;
    boxes.add_box({0, 0, 0}, {12, 12, 12}, 1, {0, 0, 0, 0, 0, 0});
    boxes.add_box({3, 3, 3}, {9, 9, 9}, 2, {1, 1, 1, 1, 1, 1});
    boxes.add_box({5, 5, 5}, {7, 7, 7}, 1, {2, 2, 2, 2, 2, 2});
    // The island in the cavity, and the hollow piece around it.
    const TetMesh mesh = expect_bound_in_every_piece(
        boxes.complex, 1, {{{5, 5, 5}, {7, 7, 7}}, {{-1, -1, -1}, {13, 13, 13}}}, 1728.0 - 216.0 + 8.0);
    EXPECT_GT(largest_tet_in(mesh, 2, {3, 3, 3}, {9, 9, 9}), 0.5) << "the bound must not spread to tissue 2";
}

TEST(Tetrahedralize, QualityBoundsHoldWhereInterfacesMaySplit)
{
    // Without -Y TetGen may split interface triangles, so on boxes (no input angle under 90 degrees) it refines
    // every tet towards the radius-edge bound; the tissue volumes stay exact. TetGen does not meet its bound
    // exactly: measured 1.576 against 1.5 (with or without its -O optimisation), so 10% over it is allowed.
    TetrahedralizeReport report;
    const TetMesh mesh =
        tetrahedralize(nested_boxes(), {.preserve_interfaces = false, .max_radius_edge_ratio = 1.5}, {}, &report);
    const auto volumes = volumes_by_tissue(mesh);
    EXPECT_NEAR(volumes.at(2), 64.0, 1e-9);
    EXPECT_NEAR(volumes.at(1), 1000.0 - 64.0, 1e-9);
    EXPECT_GT(mesh.vertices.size(), nested_boxes().vertices.size());
    EXPECT_GT(report.split_interface_triangles, 0u) << "without -Y the bound splits the boxes' faces";
    EXPECT_GT(report.interface_faces, nested_boxes().triangles.size());
    EXPECT_LE(report.max_radius_edge_ratio, 1.1 * 1.5);
    EXPECT_GE(report.min_dihedral_deg, 5.0);
}

TEST(Tetrahedralize, IntersectingBoxesAreRejectedNamingTissues)
{
    BoxComplex boxes;
    boxes.add_box({0, 0, 0}, {10, 10, 10}, 1, {0, 0, 0, 0, 0, 0});
    boxes.add_box({5, 5, 5}, {15, 15, 15}, 2, {0, 0, 0, 0, 0, 0});
    try {
        tetrahedralize(boxes.complex);
        FAIL() << "an intersecting complex was accepted";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("intersect"), std::string::npos) << message;
        EXPECT_NE(message.find("mm"), std::string::npos) << message;
    }
}

TEST(Tetrahedralize, RejectsBadOptions)
{
    EXPECT_THROW(tetrahedralize(nested_boxes(), {.max_radius_edge_ratio = 0.5}), InputError);
    TetrahedralizeOptions options;
    options.max_volume_per_tissue_mm3 = {{7, 1.0}};
    EXPECT_THROW(tetrahedralize(nested_boxes(), options), InputError);
}

// Issue 32: the optimisation level was clamped into TetGen's 0..10; out of range it is the caller's error.
TEST(Tetrahedralize, OptimisationLevelOutsideZeroToTenIsRefusedNotClamped)
{
    for (const int level : {-1, 11}) {
        try {
            tetrahedralize(nested_boxes(), {.optimisation_level = level});
            FAIL() << "level " << level << " was accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(concat("level ", level, " is outside 0..10")), std::string::npos)
                << e.what();
        }
    }
}

} // namespace
} // namespace tissuemesh::volume

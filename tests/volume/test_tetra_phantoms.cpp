// tetrahedralize() on every phantom and on the real head: conforming, every interface a tet face with its
// tissues, no tissue lost, tissue pieces as in the image, and the tets' tissues matching the voxels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <string>

#include "core/error.h"
#include "core/tet_shape.h"
#include "image/connected_components.h"
#include "image/phantom.h"
#include "io/read_label_image.h"
#include "surface/check_complex.h"
#include "surface/decimate.h"
#include "surface/extract_interfaces.h"
#include "tests/support/cli.h"
#include "volume/check_mesh.h"
#include "volume/interface_distance.h"
#include "volume/tetrahedralize.h"

namespace tissuemesh {
namespace {

struct Case {
    std::string phantom;
    double voxel_mm;
    std::map<Label, int> priority; ///< thin tissues that must stay whole (see tm-extract --priority)
};

std::string case_name(const ::testing::TestParamInfo<Case>& info)
{
    return info.param.phantom + std::to_string(static_cast<int>(info.param.voxel_mm)) + "mm";
}

/// Per tissue, the outer shells of its surface in the complex: the edge-connected pieces of its triangles
/// that enclose a positive volume (the others bound cavities). Each face-connected piece of a tissue's tets
/// has exactly one.
std::map<Label, std::size_t> outer_shells(const InterfaceComplex& complex)
{
    std::map<Label, std::vector<std::uint32_t>> by_tissue;
    for (std::uint32_t t = 0; t < complex.triangles.size(); ++t)
        for (const Label label : {complex.sides[t].from, complex.sides[t].to})
            if (label != complex.background) by_tissue[label].push_back(t);
    std::map<Label, std::size_t> shells;
    for (const auto& [label, triangles] : by_tissue) {
        std::vector<std::size_t> parent(triangles.size());
        for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = i;
        const auto root = [&](std::size_t i) {
            while (parent[i] != i) i = parent[i] = parent[parent[i]];
            return i;
        };
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> first_on_edge;
        for (std::size_t i = 0; i < triangles.size(); ++i) {
            const Triangle& tri = complex.triangles[triangles[i]];
            for (int k = 0; k < 3; ++k) {
                const auto [it, fresh] = first_on_edge.try_emplace(std::minmax(tri[k], tri[(k + 1) % 3]), i);
                if (!fresh) parent[root(i)] = root(it->second);
            }
        }
        std::map<std::size_t, double> volume;
        for (std::size_t i = 0; i < triangles.size(); ++i) {
            const std::uint32_t t = triangles[i];
            const Triangle& tri = complex.triangles[t];
            const double sign = complex.sides[t].from == label ? 1.0 : -1.0;
            volume[root(i)] +=
                sign * dot(complex.vertices[tri[0]], cross(complex.vertices[tri[1]], complex.vertices[tri[2]])) / 6;
        }
        double total = 0;
        for (const auto& [piece, v] : volume) {
            total += v;
            if (v > 0) ++shells[label];
        }
        EXPECT_GT(total, 0) << "tissue " << label << ": its surface encloses a negative volume";
    }
    return shells;
}

/// Area of the faces per tissue pair.
std::map<std::pair<Label, Label>, double> area_by_pair(const std::vector<Vec3>& vertices,
                                                       const std::vector<Triangle>& faces,
                                                       const std::vector<LabelPair>& sides)
{
    std::map<std::pair<Label, Label>, double> area;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const Triangle& t = faces[f];
        area[std::minmax(sides[f].from, sides[f].to)] +=
            0.5 * norm(cross(vertices[t[1]] - vertices[t[0]], vertices[t[2]] - vertices[t[0]]));
    }
    return area;
}

/// What a real volume may differ in from the phantoms (which allow nothing).
struct Leeway {
    /// Input triangles TetGen may split (see TetrahedralizeReport::split_interface_triangles).
    std::size_t split_triangles = 0;
    /// Whether face-connected pieces are compared with the 26-connected voxel pieces. The phantoms are built
    /// so that they agree; in real anatomy marching cubes parts voxels that touch only along an edge or at a
    /// corner, so the pieces there are compared with the outer shells of the complex only.
    bool voxel_pieces = true;
};

/// Checks the mesh of `image`'s interfaces: fit for FEM, every input triangle a face with its pair (or,
/// within the leeway, covered exactly by faces), every image tissue present with one face-connected piece
/// per outer shell of its surface in the complex, and as many as its 26-connected voxel pieces (a one-voxel
/// layer kept whole by the priority rule is one piece under 26-connectivity), and Dice >= `min_dice` per
/// tissue. Returns the check.
volume::MeshCheckReport expect_faithful_mesh(const LabelImage& image, const InterfaceComplex& complex,
                                             const TetMesh& mesh, double min_dice, const Leeway& leeway = {})
{
    const volume::MeshCheckReport check = volume::check_mesh(mesh, &image);
    EXPECT_TRUE(check.ok()) << (check.problems.empty() ? "" : check.problems.front());
    EXPECT_EQ(check.nonconforming_faces, 0u);
    EXPECT_EQ(check.inverted_tets, 0u);
    EXPECT_EQ(check.open_boundary_edges, 0u);
    EXPECT_EQ(check.missing_interface_faces, 0u);
    EXPECT_EQ(check.mislabelled_interface_faces, 0u);
    // -Y: no Steiner point on an interface, so every input triangle is a tet face, marked with its pair. A
    // split triangle becomes at least two faces, so the count grows by at least one per split, and its parts
    // cover it: the area per pair stays.
    EXPECT_GE(mesh.faces.size(), complex.triangles.size());
    EXPECT_LE(mesh.faces.size(), complex.triangles.size() + 3 * leeway.split_triangles);
    const auto input_area = area_by_pair(complex.vertices, complex.triangles, complex.sides);
    const auto mesh_area = area_by_pair(mesh.vertices, mesh.faces, mesh.face_sides);
    EXPECT_EQ(mesh_area.size(), input_area.size());
    for (const auto& [pair, area] : input_area)
        EXPECT_NEAR(mesh_area.contains(pair) ? mesh_area.at(pair) : 0.0, area, 1e-9 * area)
            << "interface " << pair.first << "|" << pair.second;
    const std::map<Label, std::size_t> shells = outer_shells(complex);
    const image::Components pieces = image::find_components(image, image::Connectivity::full26);
    std::map<Label, std::size_t> voxel_pieces;
    for (const Label label : pieces.label)
        if (label != 0) ++voxel_pieces[label];
    for (const auto& [label, count] : voxel_pieces) {
        EXPECT_TRUE(check.tissues.contains(label)) << "tissue " << label << " lost";
        if (!check.tissues.contains(label)) continue;
        const auto& stats = check.tissues.at(label);
        EXPECT_EQ(stats.components, shells.contains(label) ? shells.at(label) : 0u) << "tissue " << label;
        if (leeway.voxel_pieces) {
            EXPECT_EQ(stats.components, count) << "tissue " << label;
        }
        EXPECT_GE(stats.dice, min_dice) << "tissue " << label;
    }
    return check;
}

class TetraPhantom : public ::testing::TestWithParam<Case> {};

void check_phantom(const Case& c)
{
    const image::Phantom phantom = image::make_phantom(c.phantom, {.voxel_mm = c.voxel_mm});
    const InterfaceComplex complex = surface::extract_interfaces(phantom.image, {.priority = c.priority});
    // TetGen's mesh keeps every input triangle as a face; the improver's (on by default) keeps the interfaces on
    // the input within its tolerance instead, and the tissues, their pieces and the voxel agreement as they were.
    const TetMesh mesh = volume::tetrahedralize(complex, {.improve = false});
    const volume::MeshCheckReport tetgen = expect_faithful_mesh(phantom.image, complex, mesh, 0.97);
    const TetMesh improved = volume::tetrahedralize(complex);
    const volume::MeshCheckReport check = volume::check_mesh(improved, &phantom.image);
    EXPECT_TRUE(check.ok()) << (check.problems.empty() ? "" : check.problems.front());
    // Raw marching-cubes triangles (no remeshing) have small angles that bound the tets on them: measured
    // 8.4-15.5 deg after improvement here (0.02-3.5 before), 10 deg and more after the workflow's remeshing.
    std::printf("[ figures  ] %s %g mm: smallest dihedral %.2f -> %.2f deg\n", c.phantom.c_str(), c.voxel_mm,
                tetgen.quality.min_dihedral_deg, check.quality.min_dihedral_deg);
    EXPECT_GT(check.quality.min_dihedral_deg, std::max(5.0, tetgen.quality.min_dihedral_deg));
    for (const auto& [label, stats] : tetgen.tissues) {
        EXPECT_EQ(check.tissues.at(label).components, stats.components) << "tissue " << label;
        EXPECT_NEAR(check.tissues.at(label).volume_mm3, stats.volume_mm3, 1e-3 * stats.volume_mm3)
            << "tissue " << label;
        EXPECT_GE(check.tissues.at(label).dice, stats.dice - 1e-3) << "tissue " << label;
    }
    const volume::InterfaceDistance distance = volume::interface_distance(improved, complex);
    EXPECT_LT(distance.max_node_mm, 1e-9);
    // The improver's tolerance is 3% of the mean input edge (about a voxel here); a tenth of a voxel is the bound.
    EXPECT_LT(distance.max_face_mm, 0.1 * c.voxel_mm);
}

TEST_P(TetraPhantom, ConformingFaithfulAndWhole) { check_phantom(GetParam()); }

INSTANTIATE_TEST_SUITE_P(SmallPhantoms, TetraPhantom,
                         ::testing::Values(Case{"junction", 2, {}}, Case{"thin", 2, {{1, 1}}}, Case{"boxes", 2, {}},
                                           Case{"ellipsoids", 2, {}}),
                         case_name);

/// TetGen's quality switches (-q: radius-edge 2, min dihedral 5 deg, the defaults) away from the interfaces, on
/// tets with no node on an interface. Tets touching the interfaces are left as TetGen finds them: with -Y it
/// refuses every point that would encroach an interface triangle, so slivers between nearly coplanar interface
/// triangles stay (on the 2 mm sphere head through the surface chain: 20 of 294 k tets under 5 deg, all with
/// four nodes on interfaces). Off the interfaces TetGen keeps the dihedral bound on every tet, but the same
/// refusal (a circumcentre inside an interface triangle's diametral ball is not inserted) leaves a few tets
/// over the radius-edge bound near the interfaces. Measured here: 35 851 of 243 213 tets off the interfaces,
/// smallest dihedral 5.83 deg, 19 (0.053%) over radius-edge 2 (the worst 14.5, a 6-degree wedge with one short
/// edge between two nodes TetGen placed next to the surface).
TEST(TetraQuality, BoundsHoldForTetsOffTheInterfaces)
{
    const image::Phantom phantom = image::make_phantom("junction", {.voxel_mm = 2});
    const InterfaceComplex complex = surface::extract_interfaces(phantom.image);
    const TetMesh mesh = volume::tetrahedralize(complex, {.improve = false});
    std::vector<char> on_interface(mesh.vertices.size(), 0);
    for (const Triangle& face : mesh.faces)
        for (const std::uint32_t v : face) on_interface[v] = 1;
    std::size_t off = 0, over_ratio = 0;
    double smallest_dihedral = 180;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& tet = mesh.tets[t];
        if (on_interface[tet[0]] || on_interface[tet[1]] || on_interface[tet[2]] || on_interface[tet[3]]) continue;
        ++off;
        const TetShape shape = tet_shape(mesh, t);
        smallest_dihedral = std::min(smallest_dihedral, shape.min_dihedral_deg);
        if (shape.radius_edge_ratio > 2.0 + 1e-9) ++over_ratio;
    }
    const double share = static_cast<double>(over_ratio) / static_cast<double>(off);
    std::printf("[ figures  ] junction 2 mm: %zu of %zu tets off the interfaces, smallest dihedral %.2f deg, %zu over "
                "radius-edge 2 (%.3f%%)\n",
                off, mesh.tets.size(), smallest_dihedral, over_ratio, 100 * share);
    ASSERT_GT(off, mesh.tets.size() / 10);
    EXPECT_GE(smallest_dihedral, 5.0);
    EXPECT_LT(share, 0.002);
}

/// The 2 mm sphere head: its one-voxel CSF (37 pieces under 6-connectivity, one under 26) stays one piece
/// of tets that separates skull from brain everywhere: no tet of the skull shares a face with the brain.
TEST(TetraSpheres4, LongCsfAt2mmIsOnePieceBetweenSkullAndBrain)
{
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = 2});
    const InterfaceComplex complex = surface::extract_interfaces(phantom.image, {.priority = {{3, 1}}});
    // TetGen's mesh: expect_faithful_mesh() asks every input triangle to stay a face, which the improver's moves and
    // splits on interfaces do not keep (its own tests bound them: test_improve_mesh.cpp).
    const TetMesh mesh = volume::tetrahedralize(complex, {.improve = false});
    const volume::MeshCheckReport check = expect_faithful_mesh(phantom.image, complex, mesh, 0.97);
    for (const LabelPair& side : mesh.face_sides) {
        const bool skull_brain = (side.from == 2 && side.to == 4) || (side.from == 4 && side.to == 2);
        ASSERT_FALSE(skull_brain) << "a skull tet touches a brain tet";
    }
    EXPECT_EQ(check.tissues.at(3).components, 1u);
}

/// The 1 mm sphere head, decimated first (raw 1 mm terraces would give about 12 M tets), in its default
/// slabs (7 for its 3.2 M triangles). Before the junction-order rule and the seams decimated in slabs
/// (2026-12-03) Debian's TetGen 1.5 aborted on it decimated in slabs (insphere_s, "oriB != 0.0"), though it
/// passed check_complex(); now it meshes (this test: 167 s; in 8 slabs, tm-tetra makes 2.91 M tets).
TEST(TetraSpheres4, LongAt1mmAfterDecimation)
{
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = 1});
    InterfaceComplex complex = surface::extract_interfaces(phantom.image);
    const surface::DecimateReport report = surface::decimate(complex, {.max_distance_mm = 0.5});
    EXPECT_GT(report.slabs, 1u);
    ASSERT_TRUE(surface::check_complex(complex).ok());
    const TetMesh mesh = volume::tetrahedralize(complex, {.improve = false});
    expect_faithful_mesh(phantom.image, complex, mesh, 0.97);
}

/// The real 1 mm head with all its tissues (air cavities included), decimated first.
/// The decimated complex passes check_complex(), but TetGen 1.5 (Debian's build keeps its asserts) aborted
/// in insphere_s ("oriB != 0.0", a degenerate insphere test) after about 12 minutes, taking the process
/// with it. TetGen runs in a child process: this test fails if the process dies, and is skipped, with
/// TetGen's message, if TetGen refuses this input. Since 2026-12-03 TetGen meshes it (the whole test: 6.5 minutes);
/// its two departures from the phantoms are allowed for (see expect_faithful_mesh()).
TEST(TetraSample, LongUscHeadAfterDecimation)
{
    const LabelImage image = io::read_label_image(testing::data_path("samples/usc19-5_head.nii.gz"));
    InterfaceComplex complex = surface::extract_interfaces(image);
    surface::decimate(complex, {.max_distance_mm = 0.5});
    ASSERT_TRUE(surface::check_complex(complex).ok());
    TetMesh mesh;
    try {
        // TetGen's mesh as it keeps the input: the improver (on by default since 2026-12-04) adds nodes on
        // interfaces and slides them, so the face count and areas this test holds to are TetGen's alone.
        mesh = volume::tetrahedralize(complex, {.improve = false});
    } catch (const AlgorithmError& error) {
        EXPECT_NE(std::string(error.what()).find("TetGen"), std::string::npos) << error.what();
        GTEST_SKIP() << "known TetGen failure on this input: " << error.what();
    }
    // Measured 2026-12-03: TetGen split 2 input triangles (one point on a creased edge); face-connected
    // pieces equal the outer shells (CSF 616, from 79 26-connected voxel pieces); Dice 0.999 and above.
    expect_faithful_mesh(image, complex, mesh, 0.99, {.split_triangles = 10, .voxel_pieces = false});
}

} // namespace
} // namespace tissuemesh

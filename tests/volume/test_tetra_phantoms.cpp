// tetrahedralize() on every phantom and on the real head: conforming, every interface a tet face with its
// tissues, no tissue lost, tissue pieces as in the image, and the tets' tissues matching the voxels.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <string>

#include "core/error.h"
#include "image/connected_components.h"
#include "image/phantom.h"
#include "io/read_label_image.h"
#include "surface/check_complex.h"
#include "surface/decimate.h"
#include "surface/extract_interfaces.h"
#include "tests/support/cli.h"
#include "volume/check_mesh.h"
#include "volume/tetrahedralize.h"

namespace tissuemesh {
namespace {

struct Case {
    std::string phantom;
    double voxel_mm;
    std::map<Label, int> priority;  ///< thin tissues that must stay whole (see tm-extract --priority)
};

std::string case_name(const ::testing::TestParamInfo<Case>& info)
{
    return info.param.phantom + std::to_string(static_cast<int>(info.param.voxel_mm)) + "mm";
}

/// Checks the mesh of `image`'s interfaces: fit for FEM, every image tissue present with as many
/// face-connected pieces as its 26-connected voxel pieces (a one-voxel layer kept whole by the priority
/// rule is one piece under 26-connectivity), and Dice >= `min_dice` per tissue. Returns the check.
volume::MeshCheckReport expect_faithful_mesh(const LabelImage& image, const InterfaceComplex& complex, const TetMesh& mesh,
                          double min_dice)
{
    const volume::MeshCheckReport check = volume::check_mesh(mesh, &image);
    EXPECT_TRUE(check.ok()) << (check.problems.empty() ? "" : check.problems.front());
    EXPECT_EQ(check.nonconforming_faces, 0u);
    EXPECT_EQ(check.inverted_tets, 0u);
    EXPECT_EQ(check.open_boundary_edges, 0u);
    EXPECT_EQ(check.missing_interface_faces, 0u);
    EXPECT_EQ(check.mislabelled_interface_faces, 0u);
    // -Y: no Steiner point on an interface, so every input triangle is a tet face, marked with its pair.
    EXPECT_EQ(mesh.faces.size(), complex.triangles.size());
    const image::Components pieces = image::find_components(image, image::Connectivity::full26);
    std::map<Label, std::size_t> voxel_pieces;
    for (const Label label : pieces.label)
        if (label != 0) ++voxel_pieces[label];
    for (const auto& [label, count] : voxel_pieces) {
        EXPECT_TRUE(check.tissues.contains(label)) << "tissue " << label << " lost";
        if (!check.tissues.contains(label)) continue;
        const auto& stats = check.tissues.at(label);
        EXPECT_EQ(stats.components, count) << "tissue " << label;
        EXPECT_GE(stats.dice, min_dice) << "tissue " << label;
    }
    return check;
}

class TetraPhantom : public ::testing::TestWithParam<Case> {};

void check_phantom(const Case& c)
{
    const image::Phantom phantom = image::make_phantom(c.phantom, {.voxel_mm = c.voxel_mm});
    const InterfaceComplex complex = surface::extract_interfaces(phantom.image, {.priority = c.priority});
    const TetMesh mesh = volume::tetrahedralize(complex);
    expect_faithful_mesh(phantom.image, complex, mesh, 0.97);
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
    const TetMesh mesh = volume::tetrahedralize(complex);
    std::vector<char> on_interface(mesh.vertices.size(), 0);
    for (const Triangle& face : mesh.faces)
        for (const std::uint32_t v : face) on_interface[v] = 1;
    std::size_t off = 0, over_ratio = 0;
    double smallest_dihedral = 180;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& tet = mesh.tets[t];
        if (on_interface[tet[0]] || on_interface[tet[1]] || on_interface[tet[2]] || on_interface[tet[3]]) continue;
        ++off;
        const volume::TetShape shape = volume::tet_shape(mesh, t);
        smallest_dihedral = std::min(smallest_dihedral, shape.min_dihedral_deg);
        if (shape.radius_edge_ratio > 2.0 + 1e-9) ++over_ratio;
    }
    const double share = static_cast<double>(over_ratio) / static_cast<double>(off);
    std::printf("[ figures  ] junction 2 mm: %zu of %zu tets off the interfaces, smallest dihedral %.2f deg, %zu over "
                "radius-edge 2 (%.3f%%)\n", off, mesh.tets.size(), smallest_dihedral, over_ratio, 100 * share);
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
    const TetMesh mesh = volume::tetrahedralize(complex);
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
    const TetMesh mesh = volume::tetrahedralize(complex);
    expect_faithful_mesh(phantom.image, complex, mesh, 0.97);
}

/// The real 1 mm head with all its tissues (air cavities included), decimated first.
/// The decimated complex passes check_complex(), but TetGen 1.5 (Debian's build keeps its asserts) aborted
/// in insphere_s ("oriB != 0.0", a degenerate insphere test) after about 12 minutes, taking the process
/// with it. TetGen now runs in a child process: this test fails if the process dies, and is skipped, with
/// TetGen's message, while TetGen still refuses this input. Known failure since 2026-12-03, when TetGen
/// first meshed it (about 6 minutes): 2 interface faces more than input triangles, and more face-connected
/// pieces per tissue than 26-connected voxel pieces (CSF 616 against 79); see the README.
TEST(TetraSample, LongUscHeadAfterDecimation)
{
    const LabelImage image = io::read_label_image(testing::data_path("samples/usc19-5_head.nii.gz"));
    InterfaceComplex complex = surface::extract_interfaces(image);
    surface::decimate(complex, {.max_distance_mm = 0.5});
    ASSERT_TRUE(surface::check_complex(complex).ok());
    TetMesh mesh;
    try {
        mesh = volume::tetrahedralize(complex);
    } catch (const AlgorithmError& error) {
        EXPECT_NE(std::string(error.what()).find("TetGen"), std::string::npos) << error.what();
        GTEST_SKIP() << "known TetGen failure on this input: " << error.what();
    }
    // Real anatomy has single-voxel islands that a 0.5 mm decimation keeps: pieces are compared as for
    // the phantoms, and Dice is lower for the thin, folded tissues (grey matter, CSF) than on spheres.
    expect_faithful_mesh(image, complex, mesh, 0.9);
}

} // namespace
} // namespace tissuemesh

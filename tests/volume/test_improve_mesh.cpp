// improve_mesh(): invariants on meshes of complexes built in code (flat boxes, a thin layer, curved shells).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <map>

#include "core/error.h"
#include "core/tet_shape.h"
#include "volume/check_mesh.h"
#include "volume/detail/tetgen_adapter.h"
#include "volume/improve_mesh.h"
#include "volume/interface_distance.h"
#include "volume/tetrahedralize.h"
#include "tests/support/complexes.h"

namespace tissuemesh::volume {
namespace {

std::map<Label, double> volumes(const TetMesh& mesh)
{
    std::map<Label, double> v;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) v[mesh.tet_labels[t]] += signed_volume(mesh, t);
    return v;
}

/// Every tet positive by the exact predicate, and the mesh fit for FEM.
void expect_valid(const TetMesh& mesh)
{
    for (const Tet& t : mesh.tets)
        ASSERT_GT(
            detail::exact_side(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], mesh.vertices[t[3]]), 0);
    const MeshCheckReport check = check_mesh(mesh);
    EXPECT_TRUE(check.ok()) << (check.problems.empty() ? "" : check.problems.front());
}

/// Tets with all four nodes on interface or boundary faces and a dihedral angle below `deg`.
std::size_t interface_slivers(const TetMesh& mesh, double deg)
{
    std::vector<char> on(mesh.vertices.size(), 0);
    for (const Triangle& f : mesh.faces)
        for (const std::uint32_t v : f) on[v] = 1;
    std::size_t count = 0;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& tet = mesh.tets[t];
        if (on[tet[0]] && on[tet[1]] && on[tet[2]] && on[tet[3]] && tet_shape(mesh, t).min_dihedral_deg < deg) ++count;
    }
    return count;
}

/// The nested boxes' faces are planes, so sliding nodes on them and splitting them keeps every volume.
TEST(ImproveMesh, FlatInterfacesKeepVolumesTissuesAndPlaces)
{
    InterfaceComplex complex;
    testing::add_box(complex, {0, 0, 0}, {10, 10, 10}, 1, 0);
    testing::add_box(complex, {3, 3.5, 4}, {7, 6.5, 6.2}, 2, 1);
    TetMesh mesh = tetrahedralize(complex, {.max_volume_mm3 = 2, .improve = false});
    const auto before_volumes = volumes(mesh);
    // No deviation allowed: nodes slide only within the box faces, so every place and volume is kept exactly.
    const ImproveReport report = improve_mesh(mesh, complex, {.max_face_deviation = 0});
    expect_valid(mesh);
    std::printf("[ figures  ] nested boxes: smallest dihedral %.2f -> %.2f deg, 1st percentile %.2f -> %.2f deg\n",
                report.before.min_dihedral_deg, report.after.min_dihedral_deg, report.before.p1_min_dihedral_deg,
                report.after.p1_min_dihedral_deg);
    // The bar (10 deg); the default target (18 deg) bounds what the improver works on.
    EXPECT_GE(report.after.min_dihedral_deg, std::max(10.0, report.before.min_dihedral_deg));
    const auto after_volumes = volumes(mesh);
    for (const auto& [label, v] : before_volumes)
        EXPECT_NEAR(after_volumes.at(label), v, 1e-9 * v) << "tissue " << label;
    const InterfaceDistance distance = interface_distance(mesh, complex);
    EXPECT_LT(distance.max_node_mm, 1e-9);
    EXPECT_LT(distance.max_face_mm, 1e-9);
    EXPECT_EQ(distance.unmatched_faces, 0u);
}

/// A layer of tissue 2, 0.3 mm thick, between two blocks of tissue 1 in 3 mm steps: TetGen leaves slivers
/// with four interface nodes in it; the improver mends them, inserting nodes on the layer's faces.
TEST(ImproveMesh, ThinLayerSliversWithFourInterfaceNodes)
{
    testing::VoxelBlock block{.nx = 8, .ny = 8, .nz = 3};
    block.labels.assign(8 * 8 * 3, 1);
    for (std::size_t i = 0; i < 64; ++i) block.labels[64 + i] = 2;
    InterfaceComplex complex = testing::voxel_faces(block);
    for (Vec3& v : complex.vertices) {
        v[0] *= 3, v[1] *= 3;
        v[2] = v[2] < 1.5 ? v[2] * 3 : v[2] < 2.5 ? 3.3 : 6.3; // the layer: z in [3, 3.3]
    }
    TetMesh mesh = tetrahedralize(complex, {.improve = false});
    const std::size_t slivers = interface_slivers(mesh, 10);
    ASSERT_GT(slivers, 0u) << "TetGen left no sliver in the layer; the test needs one";
    const auto before_volumes = volumes(mesh);
    const ImproveReport report = improve_mesh(mesh, complex, {.max_face_deviation = 0});
    expect_valid(mesh);
    std::printf(
        "[ figures  ] thin layer: %zu slivers under 10 deg with four interface nodes; smallest dihedral %.2f -> %.2f "
        "deg, %zu + %zu new nodes\n",
        slivers, report.before.min_dihedral_deg, report.after.min_dihedral_deg, report.nodes_inserted,
        report.nodes_inserted_on_interfaces);
    EXPECT_EQ(interface_slivers(mesh, 10), 0u);
    EXPECT_GE(report.after.min_dihedral_deg, 10.0);
    const auto after_volumes = volumes(mesh);
    for (const auto& [label, v] : before_volumes)
        EXPECT_NEAR(after_volumes.at(label), v, 1e-9 * v) << "tissue " << label;
    EXPECT_LT(interface_distance(mesh, complex).max_face_mm, 1e-9);
}

/// Two concentric spheres: nodes slide on curved patches, and stay on them.
TEST(ImproveMesh, CurvedInterfacesStayOnTheComplexAndTheRunIsDeterministic)
{
    InterfaceComplex complex = testing::icosphere(3, 10, {0, 0, 0});
    const InterfaceComplex inner = testing::icosphere(2, 6, {0.4, -0.3, 0.2});
    const auto base = static_cast<std::uint32_t>(complex.vertices.size());
    complex.vertices.insert(complex.vertices.end(), inner.vertices.begin(), inner.vertices.end());
    for (const Triangle& t : inner.triangles) complex.add_triangle({t[0] + base, t[1] + base, t[2] + base}, {2, 1});
    TetMesh mesh = tetrahedralize(complex, {.max_volume_mm3 = 3, .improve = false});
    TetMesh again = mesh;
    const auto before_volumes = volumes(mesh);
    const ImproveReport report = improve_mesh(mesh, complex);
    expect_valid(mesh);
    std::printf("[ figures  ] two spheres: smallest dihedral %.2f -> %.2f deg, 1st percentile %.2f -> %.2f deg\n",
                report.before.min_dihedral_deg, report.after.min_dihedral_deg, report.before.p1_min_dihedral_deg,
                report.after.p1_min_dihedral_deg);
    EXPECT_GE(report.after.min_dihedral_deg, std::max(10.0, report.before.min_dihedral_deg));
    EXPECT_GT(report.after.p1_min_dihedral_deg, report.before.p1_min_dihedral_deg);
    const InterfaceDistance distance = interface_distance(mesh, complex);
    EXPECT_LT(distance.max_node_mm, 1e-9);
    // Chords of the 1.7 mm triangles on a 6 mm sphere: within a few hundredths of a mm.
    EXPECT_LT(distance.max_face_mm, 0.1);
    const auto after_volumes = volumes(mesh);
    for (const auto& [label, v] : before_volumes)
        EXPECT_NEAR(after_volumes.at(label), v, 1e-3 * v) << "tissue " << label;
    improve_mesh(again, complex);
    EXPECT_EQ(again.vertices, mesh.vertices);
    EXPECT_EQ(again.tets, mesh.tets);
    EXPECT_EQ(again.faces, mesh.faces);
}

/// Without a complex the mesh's own faces are the reference: the same invariants.
TEST(ImproveMesh, OwnFacesServeAsTheReference)
{
    const InterfaceComplex complex = testing::icosphere(2, 8, {0, 0, 0});
    TetMesh mesh = tetrahedralize(complex, {.max_volume_mm3 = 4, .improve = false});
    const double volume = volumes(mesh).at(1);
    const ImproveReport report = improve_mesh(mesh);
    expect_valid(mesh);
    EXPECT_GE(report.after.min_dihedral_deg, report.before.min_dihedral_deg);
    EXPECT_NEAR(volumes(mesh).at(1), volume, 1e-3 * volume);
    EXPECT_LT(interface_distance(mesh, complex).max_node_mm, 1e-9);
}

TEST(ImproveMesh, RejectsBadOptions)
{
    InterfaceComplex complex;
    testing::add_box(complex, {0, 0, 0}, {1, 1, 1}, 1, 0);
    TetMesh mesh = tetrahedralize(complex, {.improve = false});
    EXPECT_THROW(improve_mesh(mesh, complex, {.target_dihedral_deg = 0}), InputError);
    EXPECT_THROW(improve_mesh(mesh, complex, {.target_dihedral_deg = 80}), InputError);
}

} // namespace
} // namespace tissuemesh::volume

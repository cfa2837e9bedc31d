// Constrained refinement of a tm-tetra mesh: interfaces kept face by face, labels never cross them, and the
// total error volume never rises.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "core/error.h"
#include "surface/detail/triangle_distance.h"
#include "tests/support/programs.h"
#include "volume/assess.h"
#include "volume/check_mesh.h"
#include "volume/detail/tet_quality.h"
#include "volume/refine.h"
#include "volume/tetrahedralize.h"

namespace tissuemesh::volume {
namespace {

using Meshed = testing::MeshedPhantom;

/// The junction phantom (three tissues meeting along a circle) at 4 mm through tm-extract's and tm-tetra's steps.
const Meshed& junction() { return testing::meshed_phantom("junction", 4); }

using testing::tissue_volumes;

class RefineConstrained : public ::testing::TestWithParam<Placement> {};

TEST_P(RefineConstrained, KeepsEveryInterfaceAndNeverRaisesTheErrorVolume)
{
    const Meshed& m = junction();
    RefineReport report;
    // Refinement's own promise, without the improver (which slides interface nodes: the next test).
    const TetMesh refined =
        refine(m.image, &m.mesh, {.placement = GetParam(), .max_iterations = 2, .improve = false}, {}, &report);
    ASSERT_EQ(report.iterations.size(), 3u) << report.stop_reason;
    EXPECT_GT(refined.vertices.size(), m.mesh.vertices.size());
    const MeshCheckReport check = check_mesh(refined, &m.image);
    EXPECT_TRUE(check.ok()) << (check.problems.empty() ? "" : check.problems.front());
    // The very same interface faces: old nodes keep their indices and no cavity crosses or splits a face; the nodes
    // on them keep their places.
    EXPECT_EQ(refined.faces, m.mesh.faces);
    EXPECT_EQ(refined.face_sides, m.mesh.face_sides);
    for (const Triangle& face : m.mesh.faces)
        for (const std::uint32_t v : face) ASSERT_EQ(refined.vertices[v], m.mesh.vertices[v]);
    // Tissue regions unchanged: volumes agree to round-off (different tets summed).
    const auto before = tissue_volumes(m.mesh), after = tissue_volumes(refined);
    ASSERT_EQ(before.size(), after.size());
    for (const auto& [label, volume] : before)
        EXPECT_NEAR(after.at(label), volume, 1e-9 * volume) << "tissue " << label;
    // The same regions hold the same voxel centres: the error volume is exactly that of the start, every round.
    const double start = report.iterations.front().total_error_volume_mm3;
    for (const RefineIteration& it : report.iterations)
        EXPECT_LE(it.total_error_volume_mm3, start) << "round " << it.iteration;
    EXPECT_EQ(assess_elements(refined, m.image).total_error_volume_mm3, start);
}

// By default the refined mesh is improved as tm-tetra's is: interface nodes slide on the interfaces and nodes
// may be added, so the regions change a little and the error volume is measured again (it was reported as the
// last round's, which an improved mesh no longer has).
TEST(RefineConstrained, TheDefaultImprovementKeepsTheRegionsAndMeasuresTheErrorVolumeAgain)
{
    const Meshed& m = junction();
    RefineReport report;
    const TetMesh refined = refine(m.image, &m.mesh, {.max_iterations = 2}, {}, &report);
    ASSERT_TRUE(report.improved);
    const MeshCheckReport check = check_mesh(refined, &m.image);
    EXPECT_TRUE(check.ok()) << (check.problems.empty() ? "" : check.problems.front());
    EXPECT_GE(report.improvement.after.min_dihedral_deg, report.improvement.before.min_dihedral_deg);
    EXPECT_EQ(report.improvement.after.min_dihedral_deg, check.quality.min_dihedral_deg);
    const auto before = tissue_volumes(m.mesh), after = tissue_volumes(refined);
    ASSERT_EQ(before.size(), after.size());
    for (const auto& [label, volume] : before)
        EXPECT_NEAR(after.at(label), volume, 2e-4 * volume) << "tissue " << label;
    EXPECT_EQ(report.improved_error_volume_mm3, assess_elements(refined, m.image).total_error_volume_mm3);
    const double start = report.iterations.front().total_error_volume_mm3;
    EXPECT_NEAR(report.improved_error_volume_mm3, start, 0.02 * start);
}

// Regression: nodes placed within 1e-3 mm of an interface face crashed TetGen (suppresssteinerpoints) in the
// third round on the demo's sphere head; new nodes now keep the node spacing (half a voxel) from interfaces.
TEST(RefineConstrainedClearance, NewNodesKeepHalfAVoxelFromEveryInterface)
{
    const Meshed& m = junction();
    RefineReport report;
    // The rule is one of placement: the improver's moves of inner nodes afterwards (on by default) do not keep it.
    const TetMesh refined = refine(m.image, &m.mesh, {.max_iterations = 1, .improve = false}, {}, &report);
    // One round: our nodes follow the old ones; TetGen's own Steiner points (if any) come after them.
    const std::size_t added = report.iterations.back().added_nodes;
    ASSERT_GT(added, 50u); // enough to test (94 since the improver's 22-degree target shaped the start mesh)
    ASSERT_GE(refined.vertices.size(), m.mesh.vertices.size() + added);
    double closest = 1e300;
    for (std::size_t v = m.mesh.vertices.size(); v < m.mesh.vertices.size() + added; ++v)
        for (const Triangle& f : refined.faces)
            closest = std::min(closest,
                               distance(refined.vertices[v],
                                        surface::detail::closest_point_on_triangle(
                                            refined.vertices[v],
                                            {refined.vertices[f[0]], refined.vertices[f[1]], refined.vertices[f[2]]})));
    EXPECT_GE(closest, 0.5 * 4.0 - 1e-9); // 4 mm voxels
}

/// The smallest of the tets' smallest dihedral sines (detail::min_sine(): small for flat tets, whether an angle
/// is near 0 or 180 degrees).
double smallest_sine(const TetMesh& mesh)
{
    double smallest = 1;
    for (const Tet& tet : mesh.tets)
        smallest = std::min(smallest, detail::min_sine({mesh.vertices[tet[0]], mesh.vertices[tet[1]],
                                                        mesh.vertices[tet[2]], mesh.vertices[tet[3]]}));
    return smallest;
}

// Each new node goes into the mesh as it is, in its cavity: every tet without a new node is a tet of the start
// mesh (the same nodes in the same order, the same tissue), and no cavity leaves a tet flatter than 10 degrees
// (in sine) unless the tets it replaced were flatter still.
TEST(RefineConstrained, NewNodesGoInCavitiesAndEveryOtherTetStays)
{
    const Meshed& m = junction();
    RefineReport report;
    const TetMesh refined = refine(m.image, &m.mesh, {.max_iterations = 2, .improve = false}, {}, &report);
    ASSERT_EQ(report.iterations.size(), 3u) << report.stop_reason;
    std::size_t added = 0;
    for (const RefineIteration& it : report.iterations) added += it.added_nodes;
    ASSERT_GT(added, 50u);
    ASSERT_EQ(refined.vertices.size(), m.mesh.vertices.size() + added);
    std::set<std::pair<Tet, Label>> start;
    for (std::size_t t = 0; t < m.mesh.tets.size(); ++t) start.insert({m.mesh.tets[t], m.mesh.tet_labels[t]});
    std::size_t kept = 0, with_new_node = 0;
    for (std::size_t t = 0; t < refined.tets.size(); ++t) {
        const Tet& tet = refined.tets[t];
        if (std::any_of(tet.begin(), tet.end(), [&](std::uint32_t v) { return v >= m.mesh.vertices.size(); })) {
            ++with_new_node;
            continue;
        }
        EXPECT_TRUE(start.count({tet, refined.tet_labels[t]})) << "tet " << t << " is neither old nor at a new node";
        ++kept;
    }
    EXPECT_GT(kept, start.size() / 2);
    EXPECT_GT(with_new_node, 4 * added);
    EXPECT_GE(smallest_sine(refined), std::min(smallest_sine(m.mesh), detail::sine_of_deg(10)));
    const MeshCheckReport check = check_mesh(refined, &m.image);
    EXPECT_TRUE(check.ok()) << (check.problems.empty() ? "" : check.problems.front());
}

// RefineOptions::tetgen_rebuild, the refinement before cavities: every round's mesh made again by TetGen from its
// nodes and faces, which keeps the same promise.
TEST(RefineConstrained, TetGenRebuildKeepsEveryInterfaceToo)
{
    const Meshed& m = junction();
    RefineReport report;
    const TetMesh refined =
        refine(m.image, &m.mesh, {.max_iterations = 1, .improve = false, .tetgen_rebuild = true}, {}, &report);
    ASSERT_EQ(report.iterations.size(), 2u) << report.stop_reason;
    EXPECT_GT(refined.vertices.size(), m.mesh.vertices.size());
    const MeshCheckReport check = check_mesh(refined, &m.image);
    EXPECT_TRUE(check.ok()) << (check.problems.empty() ? "" : check.problems.front());
    EXPECT_EQ(refined.faces, m.mesh.faces);
    const auto before = tissue_volumes(m.mesh), after = tissue_volumes(refined);
    ASSERT_EQ(before.size(), after.size());
    for (const auto& [label, volume] : before)
        EXPECT_NEAR(after.at(label), volume, 1e-9 * volume) << "tissue " << label;
    EXPECT_EQ(assess_elements(refined, m.image).total_error_volume_mm3,
              report.iterations.front().total_error_volume_mm3);
}

INSTANTIATE_TEST_SUITE_P(Placements, RefineConstrained,
                         ::testing::Values(Placement::longest_edge, Placement::material_centroid),
                         [](const ::testing::TestParamInfo<Placement>& param) {
                             std::string name = placement_name(param.param);
                             std::erase(name, '-');
                             return name;
                         });

TEST(RefineInput, BadOptionsAndNamesAreInputErrors)
{
    const LabelImage image({4, 4, 4}, {1, 1, 1});
    EXPECT_THROW(refine(LabelImage{}, nullptr), InputError);
    EXPECT_THROW(refine(image, nullptr, {.batch_fraction = 2}), InputError);
    EXPECT_THROW(parse_placement("circumcentre"), InputError);
    EXPECT_EQ(parse_placement("material-centroid"), Placement::material_centroid);
    TetMesh empty;
    EXPECT_THROW(refine(image, &empty), InputError);
}

} // namespace
} // namespace tissuemesh::volume

// improve_mesh(): invariants on meshes of complexes built in code (flat boxes, a thin layer, curved shells), and
// in mesh parts side by side (cutting and merging, frozen nodes, the same bytes whatever the thread count).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <map>
#include <omp.h>
#include <set>

#include "core/error.h"
#include "core/tet_adjacency.h"
#include "core/tet_shape.h"
#include "image/phantom.h"
#include "surface/decimate.h"
#include "surface/extract_surface_nets.h"
#include "surface/remesh.h"
#include "volume/check_mesh.h"
#include "volume/detail/improver.h"
#include "volume/detail/insert_node.h"
#include "volume/detail/interface_flip.h"
#include "volume/detail/mesh_parts.h"
#include "volume/detail/smooth_node.h"
#include "volume/detail/surface_reference.h"
#include "volume/detail/tetgen_adapter.h"
#include "volume/detail/work_mesh.h"
#include "io/surface_io.h"
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

/// Prints the improver's figures for `what` and checks that the smallest angle reached 10 degrees (or was no lower
/// than before) and the 1st percentile rose.
void expect_angles_raised(const char* what, const ImproveReport& report)
{
    std::printf("[ figures  ] %s: smallest dihedral %.2f -> %.2f deg, 1st percentile %.2f -> %.2f deg\n", what,
                report.before.min_dihedral_deg, report.after.min_dihedral_deg, report.before.p1_min_dihedral_deg,
                report.after.p1_min_dihedral_deg);
    EXPECT_GE(report.after.min_dihedral_deg, std::max(10.0, report.before.min_dihedral_deg));
    EXPECT_GT(report.after.p1_min_dihedral_deg, report.before.p1_min_dihedral_deg);
}

/// Two concentric spheres of tissues 1 (outer shell) and 2, off centre.
InterfaceComplex two_spheres()
{
    InterfaceComplex complex = testing::icosphere(3, 10, {0, 0, 0});
    const InterfaceComplex inner = testing::icosphere(2, 6, {0.4, -0.3, 0.2});
    const auto base = static_cast<std::uint32_t>(complex.vertices.size());
    complex.vertices.insert(complex.vertices.end(), inner.vertices.begin(), inner.vertices.end());
    for (const Triangle& t : inner.triangles) complex.add_triangle({t[0] + base, t[1] + base, t[2] + base}, {2, 1});
    return complex;
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

/// A layer of tissue 2, 0.3 mm thick, between two blocks of tissue 1 in 3 mm steps (z in [3, 3.3]).
InterfaceComplex thin_layer()
{
    testing::VoxelBlock block{.nx = 8, .ny = 8, .nz = 3};
    block.labels.assign(8 * 8 * 3, 1);
    for (std::size_t i = 0; i < 64; ++i) block.labels[64 + i] = 2;
    InterfaceComplex complex = testing::voxel_faces(block);
    for (Vec3& v : complex.vertices) {
        v[0] *= 3, v[1] *= 3;
        v[2] = v[2] < 1.5 ? v[2] * 3 : v[2] < 2.5 ? 3.3 : 6.3;
    }
    return complex;
}

/// The thin layer: TetGen leaves slivers with four interface nodes in it; the improver mends them, inserting nodes
/// on the layer's faces.
TEST(ImproveMesh, ThinLayerSliversWithFourInterfaceNodes)
{
    const InterfaceComplex complex = thin_layer();
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

/// Insertion judges each candidate as it is tried (insert_for_tet's `kept`, the improver's voxel and outer-boundary
/// rules): when the best candidate is refused, the next best is inserted, and what the judge refused leaves no trace.
/// Judged once after the best was chosen, a refused best failed the tet (the liver's worst tet with
/// tm-tetra --layer-points: 11.86 degrees, 16.30 since).
TEST(ImproveMesh, InsertionTriesTheNextCandidateWhenTheJudgeRefusesOne)
{
    const InterfaceComplex complex = thin_layer();
    const TetMesh mesh = tetrahedralize(complex, {.improve = false});
    const detail::SurfaceReference reference(complex);
    const detail::WorkMesh start(mesh);
    std::uint32_t worst = 0;
    for (std::uint32_t t = 1; t < start.tet_slots(); ++t)
        if (start.quality(t) < start.quality(worst)) worst = t;
    // Unjudged: where the best candidate puts its node.
    detail::WorkMesh free_mesh(mesh);
    ASSERT_TRUE(detail::insert_for_tet(free_mesh, worst, reference, true, 0.0));
    ASSERT_EQ(free_mesh.node_count(), mesh.vertices.size() + 1);
    const Vec3 best = free_mesh.point(static_cast<std::uint32_t>(mesh.vertices.size()));
    // The judge refuses a node there: another candidate is inserted, and only it.
    detail::WorkMesh judged(mesh);
    std::size_t refused = 0, asked = 0;
    const auto refuse_best = [&](std::size_t mark) {
        ++asked;
        if (distance(judged.point(static_cast<std::uint32_t>(judged.node_count() - 1)), best) > 1e-12) return true;
        ++refused;
        judged.rollback(mark);
        return false;
    };
    ASSERT_TRUE(detail::insert_for_tet(judged, worst, reference, true, 0.0, refuse_best));
    EXPECT_GE(refused, 1u);
    EXPECT_GT(asked, refused);
    ASSERT_EQ(judged.node_count(), mesh.vertices.size() + 1);
    EXPECT_GT(distance(judged.point(static_cast<std::uint32_t>(mesh.vertices.size())), best), 1e-12);
    EXPECT_FALSE(judged.alive(worst));
    EXPECT_GT(judged.balance_since(0).after, judged.balance_since(0).before);
    // A judge that refuses everything: no insertion, the mesh as it was.
    detail::WorkMesh refused_all(mesh);
    ASSERT_FALSE(detail::insert_for_tet(refused_all, worst, reference, true, 0.0, [&](std::size_t mark) {
        refused_all.rollback(mark);
        return false;
    }));
    EXPECT_EQ(refused_all.node_count(), mesh.vertices.size());
    EXPECT_EQ(refused_all.tet_count(), start.tet_count());
    EXPECT_TRUE(refused_all.alive(worst));
}

/// Two concentric spheres: nodes slide on curved patches, and stay on them.
TEST(ImproveMesh, CurvedInterfacesStayOnTheComplexAndTheRunIsDeterministic)
{
    const InterfaceComplex complex = two_spheres();
    TetMesh mesh = tetrahedralize(complex, {.max_volume_mm3 = 3, .improve = false});
    TetMesh again = mesh;
    const auto before_volumes = volumes(mesh);
    const ImproveReport report = improve_mesh(mesh, complex);
    expect_valid(mesh);
    expect_angles_raised("two spheres", report);
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

/// The volume allowance given to one run of the improver bounds each tissue's drift in mm^3, whatever its volume in the
/// mesh: improve_mesh() gives the last round after the parts (a few hundred tets) its share of the whole mesh's.
TEST(ImproveMesh, AVolumeAllowanceBoundsEachTissuesDrift)
{
    const InterfaceComplex complex = two_spheres();
    const TetMesh start = tetrahedralize(complex, {.max_volume_mm3 = 3, .improve = false});
    const detail::SurfaceReference reference(complex);
    const auto before = volumes(start);
    const auto largest_drift = [&](const std::map<Label, double>& allowance) {
        TetMesh mesh = start;
        ImproveReport report;
        detail::improve_in_place(mesh, reference, nullptr, {}, report, {}, {}, allowance);
        expect_valid(mesh);
        std::map<Label, double> drift;
        for (const auto& [label, volume] : volumes(mesh)) drift[label] = std::abs(volume - before.at(label));
        return std::pair{drift, report.smoothed_nodes};
    };
    // None allowed: every move of a node on the spheres changes a volume, so only inner nodes move.
    const auto [none, moves_without] = largest_drift({{1, 0.0}, {2, 0.0}});
    for (const auto& [label, drift] : none) EXPECT_LT(drift, 1e-9 * before.at(label)) << "tissue " << label;
    // The default: ImproveOptions::max_volume_change (2e-4) of each tissue's volume.
    const auto [by_default, moves_by_default] = largest_drift({});
    for (const auto& [label, drift] : by_default) EXPECT_LE(drift, 2e-4 * before.at(label) * (1 + 1e-9));
    // Ten times the default, in mm^3: the drift may exceed the default's bound, never the allowance.
    std::map<Label, double> wide;
    for (const auto& [label, volume] : before) wide[label] = 2e-3 * volume;
    const auto [widened, moves_widened] = largest_drift(wide);
    double beyond_default = 0;
    for (const auto& [label, drift] : widened) {
        EXPECT_LE(drift, wide.at(label) * (1 + 1e-9)) << "tissue " << label;
        beyond_default = std::max(beyond_default, drift / (2e-4 * before.at(label)));
    }
    std::printf("[ figures  ] two spheres: %zu, %zu, %zu node moves with no, the default and ten times the default "
                "volume change; the last drifts %.2f times the default's bound\n",
                moves_without, moves_by_default, moves_widened, beyond_default);
    EXPECT_LT(moves_without, moves_widened);
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

/// data/regression/improver-parts-lowered-worst-tet.ply: the 4-shell icosphere head of the fem tests at level 3 (its
/// vertices rounded a little differently), meshed with 30 mm^3 tets: 110 k, so the improver works in 2 parts, then a
/// band. A version of the improver (the twenty-first session's volume leeway, reverted) lowered its worst tet from
/// TetGen's 6.34 to 5.23 degrees here, in 2 parts and not in 1: the worst tet must never get worse.
TEST(ImproveMesh, FourShellHeadInPartsNeverLowersTheWorstTet)
{
    const InterfaceComplex complex =
        io::read_surface(std::string(TM_DATA_DIR) + "/regression/improver-parts-lowered-worst-tet.ply");
    TetrahedralizeReport report;
    const TetMesh mesh = tetrahedralize(complex, {.max_volume_mm3 = 30}, {}, &report);
    ASSERT_TRUE(report.improved);
    EXPECT_EQ(report.improvement.parts, 2u);
    std::printf("[ figures  ] %zu tets: smallest dihedral %.2f -> %.2f deg\n", mesh.tets.size(),
                report.improvement.before.min_dihedral_deg, report.improvement.after.min_dihedral_deg);
    expect_valid(mesh);
    EXPECT_GE(report.improvement.after.min_dihedral_deg, report.improvement.before.min_dihedral_deg);
}

/// Each tissue's Dice against `image`, by label.
std::map<Label, double> dice_of(const TetMesh& mesh, const LabelImage& image)
{
    std::map<Label, double> dice;
    for (const auto& [label, tissue] : check_mesh(mesh, &image).tissues) dice[label] = tissue.dice;
    return dice;
}

/// The `thin` phantom at 2 mm (a one-voxel shell) through surface nets, decimation and remeshing, meshed without
/// improvement: with the voxels given, no interface edit carries a voxel centre next to another tissue across, so no
/// tissue's Dice falls; without them, the shell's falls.
TEST(ImproveMesh, KeepingTheVoxelSidesKeepsEveryDice)
{
    const image::Phantom phantom = image::make_phantom("thin", {.voxel_mm = 2.0});
    InterfaceComplex complex = surface::extract_surface_nets(phantom.image, {.priority = {{1, 1}}});
    surface::decimate(complex, {.max_distance_mm = 0.5, .max_edge_mm = 8, .max_normal_change_deg = 45});
    surface::remesh(complex, {.target_edge_mm = 6, .voxel_image = &phantom.image});
    const TetMesh start = tetrahedralize(complex, {.improve = false});
    TetMesh plain = start, kept = start;
    const ImproveReport without = improve_mesh(plain, complex);
    const ImproveReport with = improve_mesh(kept, complex, {.voxel_image = &phantom.image});
    expect_valid(kept);
    // This chain's shell holds tets the improver lifts to 9 degrees with or without the voxels (the workflow's edges
    // by thickness reach 14): their worst is no lower.
    EXPECT_GE(with.after.min_dihedral_deg, without.after.min_dihedral_deg - 1e-9);
    EXPECT_GT(with.after.p1_min_dihedral_deg, with.before.p1_min_dihedral_deg);
    EXPECT_EQ(without.refused_by_voxels, 0u);
    EXPECT_GT(with.refused_by_voxels, 0u);
    const std::map<Label, double> before = dice_of(start, phantom.image), after_without = dice_of(plain, phantom.image),
                                  after_with = dice_of(kept, phantom.image);
    double drop_without = 0, drop_with = 0;
    for (const auto& [label, dice] : before) {
        drop_without = std::max(drop_without, dice - after_without.at(label));
        drop_with = std::max(drop_with, dice - after_with.at(label));
        EXPECT_GE(after_with.at(label), dice - 1e-5) << "tissue " << label;
    }
    std::printf("[ figures  ] thin 2 mm: worst Dice drop %.5f without the voxels, %.5f with (%zu edits refused); "
                "smallest dihedral %.2f and %.2f deg\n",
                drop_without, drop_with, with.refused_by_voxels, without.after.min_dihedral_deg,
                with.after.min_dihedral_deg);
    EXPECT_GT(drop_without, drop_with);
    // A mesh beside the image is refused, not judged against no voxel.
    TetMesh moved = start;
    for (Vec3& p : moved.vertices) p = p + Vec3{500, 0, 0};
    EXPECT_THROW(improve_mesh(moved, {.voxel_image = &phantom.image}), InputError);
}

TEST(SurfaceReference, HintsChangeNoAnswer)
{
    // The smoothing asks the reference again and again about points that move a little and passes the triangle
    // found last as a hint: the answers must be those without one, whatever the hint (near, far, of another
    // tissue pair, out of range).
    const InterfaceComplex complex = two_spheres();
    const detail::SurfaceReference reference(complex);
    const auto count = static_cast<std::uint32_t>(complex.triangles.size());
    std::uint32_t carried = ~0u, patch_hits = 0, within_hits = 0;
    for (std::uint32_t i = 0; i < 400; ++i) {
        // Points around the inner sphere (radius 6 about (0.4, -0.3, 0.2)), on it and up to 0.6 mm off it.
        const double theta = 0.37 * i, z = std::fmod(0.013 * i * i, 2.0) - 1.0, r = std::sqrt(1 - z * z);
        const double radius = 6 + 0.003 * static_cast<double>(i % 200) - 0.3;
        const Vec3 p = Vec3{0.4, -0.3, 0.2} + radius * Vec3{r * std::cos(theta), r * std::sin(theta), z};
        for (const double reach : {0.05, 0.4, 3.0}) {
            const std::optional<Vec3> plain = reference.onto_patch(p, 1, 2, reach);
            const double tolerance = 0.1 * reach;
            const bool near = reference.within(p, 2, 1, tolerance);
            for (const std::uint32_t start : {~0u, 0u, count - 1, (i * 7919u) % count, count + 5, carried}) {
                std::uint32_t hint = start;
                const std::optional<Vec3> hinted = reference.onto_patch(p, 2, 1, reach, &hint);
                ASSERT_EQ(plain.has_value(), hinted.has_value()) << "point " << i << ", reach " << reach;
                if (plain) {
                    EXPECT_EQ(*plain, *hinted) << "point " << i << ", reach " << reach << ", hint " << start;
                    EXPECT_LT(hint, count);
                    carried = hint, ++patch_hits;
                }
                std::uint32_t within_hint = start;
                EXPECT_EQ(near, reference.within(p, 1, 2, tolerance, &within_hint)) << "point " << i;
                within_hits += near;
            }
        }
    }
    // Both answers occur (the comparisons above could fail).
    EXPECT_GT(patch_hits, 0u);
    EXPECT_GT(within_hits, 0u);
    EXPECT_LT(within_hits, 400u * 3 * 6);
}

TEST(ImproveMesh, RejectsBadOptions)
{
    InterfaceComplex complex;
    testing::add_box(complex, {0, 0, 0}, {1, 1, 1}, 1, 0);
    TetMesh mesh = tetrahedralize(complex, {.improve = false});
    EXPECT_THROW(improve_mesh(mesh, complex, {.target_dihedral_deg = 0}), InputError);
    EXPECT_THROW(improve_mesh(mesh, complex, {.target_dihedral_deg = 80}), InputError);
}

// ---- In mesh parts side by side (ImproveOptions::parts): cutting and merging, frozen nodes, threads.

/// Tets as sorted node sets with their tissues, and faces as sorted node sets with their tissue pairs: the
/// mesh whatever the order of its lists.
std::set<std::pair<std::array<std::uint32_t, 4>, Label>> tet_set(const TetMesh& mesh)
{
    std::set<std::pair<std::array<std::uint32_t, 4>, Label>> out;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        std::array<std::uint32_t, 4> key = mesh.tets[t];
        std::sort(key.begin(), key.end());
        out.insert({key, mesh.tet_labels[t]});
    }
    return out;
}
std::set<std::array<std::uint32_t, 3>> face_set(const TetMesh& mesh)
{
    std::set<std::array<std::uint32_t, 3>> out;
    for (const Triangle& f : mesh.faces) {
        std::array<std::uint32_t, 3> key = f;
        std::sort(key.begin(), key.end());
        out.insert(key);
    }
    return out;
}

TEST(ImproveInParts, PartsCutAndMergedUneditedGiveTheMeshBack)
{
    const InterfaceComplex complex = two_spheres();
    const TetMesh mesh = tetrahedralize(complex, {.max_volume_mm3 = 2, .improve = false});
    const detail::Cut cut = detail::cut_across(mesh, 3);
    ASSERT_EQ(cut.between.size(), 2u);
    const detail::PartCutter cutter(mesh);
    const TetAdjacency adjacency(mesh.tets, mesh.vertices.size());
    std::vector<std::vector<std::uint32_t>> tets(3);
    for (std::uint32_t t = 0; t < mesh.tets.size(); ++t) tets[cut.part_of[t]].push_back(t);
    std::vector<detail::MeshPart> parts;
    std::vector<TetMesh> edited;
    for (std::uint32_t k = 0; k < 3; ++k) {
        // About a third of the tets each.
        EXPECT_NEAR(static_cast<double>(tets[k].size()), static_cast<double>(mesh.tets.size()) / 3, 1.0);
        parts.push_back(cutter.part(tets[k]));
        edited.push_back(parts.back().mesh);
        // Every face of a part's tet that another part's tet shares has only frozen nodes.
        for (const std::uint32_t t : tets[k])
            for (int i = 0; i < 4; ++i) {
                const std::uint32_t n = adjacency.across(t, i);
                if (n == no_tet || cut.part_of[n] == k) continue;
                for (int j = 0; j < 4; ++j) {
                    if (j == i) continue;
                    const std::uint32_t v = mesh.tets[t][static_cast<std::size_t>(j)];
                    const auto local = std::lower_bound(parts[k].from_node.begin(), parts[k].from_node.end(), v) -
                                       parts[k].from_node.begin();
                    EXPECT_TRUE(parts[k].frozen[static_cast<std::size_t>(local)]);
                }
            }
    }
    // The middle part meets both others: it has the most frozen nodes.
    const auto frozen = [&](std::size_t k) { return std::count(parts[k].frozen.begin(), parts[k].frozen.end(), 1); };
    EXPECT_GT(frozen(1), frozen(0));
    EXPECT_GT(frozen(1), frozen(2));
    const TetMesh merged = detail::merge_parts(mesh, cut.part_of, parts, edited);
    EXPECT_EQ(merged.vertices, mesh.vertices);
    EXPECT_EQ(tet_set(merged), tet_set(mesh));
    EXPECT_EQ(merged.faces.size(), mesh.faces.size());
    EXPECT_EQ(face_set(merged), face_set(mesh));
}

// The bands after the parts take each group of tets joined through the nodes of tets to improve whole
// (improve_mesh.cpp): split between two bands, a tet midway between two cuts had its nodes frozen in both (the 1 mm
// usc19-5 head's refined mesh kept a 4.77-degree tet).
TEST(ImproveInParts, GroupsOfTouchingTetsAreWholeAndApart)
{
    const TetMesh mesh = tetrahedralize(two_spheres(), {.max_volume_mm3 = 2, .improve = false});
    // Two seeds at the ends of the mesh's longest side, with two rings of tets around each.
    const detail::Cut cut = detail::cut_across(mesh, 2);
    std::vector<char> seeds(mesh.tets.size(), 0);
    const auto first_in = [&](std::uint32_t part) {
        return static_cast<std::uint32_t>(std::find(cut.part_of.begin(), cut.part_of.end(), part) -
                                          cut.part_of.begin());
    };
    seeds[first_in(0)] = seeds[first_in(1)] = 1;
    // Far apart: the first in part 0 and a tet of part 1 farthest from it.
    std::uint32_t far = first_in(1);
    const auto centroid = [&](std::uint32_t t) {
        Vec3 c{0, 0, 0};
        for (const std::uint32_t v : mesh.tets[t]) c = c + 0.25 * mesh.vertices[v];
        return c;
    };
    for (std::uint32_t t = 0; t < mesh.tets.size(); ++t)
        if (distance(centroid(t), centroid(first_in(0))) > distance(centroid(far), centroid(first_in(0)))) far = t;
    seeds[first_in(1)] = 0, seeds[far] = 1;
    const std::vector<char> around = detail::tets_around(mesh, seeds, 2);
    const std::vector<std::uint32_t> groups = detail::groups_of(mesh, around);
    std::set<std::uint32_t> roots;
    std::vector<std::uint32_t> group_at(mesh.vertices.size(), detail::no_part);
    for (std::uint32_t t = 0; t < mesh.tets.size(); ++t) {
        ASSERT_EQ(groups[t] == detail::no_part, !around[t]) << "tet " << t;
        if (!around[t]) continue;
        EXPECT_LE(groups[t], t);
        EXPECT_EQ(groups[groups[t]], groups[t]) << "a group's root is its own";
        roots.insert(groups[t]);
        for (const std::uint32_t v : mesh.tets[t]) {
            if (group_at[v] == detail::no_part) group_at[v] = groups[t];
            EXPECT_EQ(group_at[v], groups[t]) << "tets sharing node " << v << " are in one group";
        }
    }
    EXPECT_EQ(roots.size(), 2u);
    // Joined only through the seeds' nodes (as the bands are): the seeds' stars, each whole with its seed.
    std::vector<char> seed_nodes(mesh.vertices.size(), 0);
    for (std::uint32_t t = 0; t < mesh.tets.size(); ++t)
        if (seeds[t])
            for (const std::uint32_t v : mesh.tets[t]) seed_nodes[v] = 1;
    const std::vector<char> stars = detail::tets_around(mesh, seeds, 1);
    const std::vector<std::uint32_t> star_groups = detail::groups_of(mesh, stars, seed_nodes);
    for (std::uint32_t t = 0; t < mesh.tets.size(); ++t) {
        if (!stars[t]) continue;
        const auto at_far = [&](std::uint32_t v) {
            return std::ranges::find(mesh.tets[far], v) != mesh.tets[far].end();
        };
        const std::uint32_t seed = std::ranges::any_of(mesh.tets[t], at_far) ? far : first_in(0);
        EXPECT_EQ(star_groups[t], star_groups[seed]) << "tet " << t;
    }
    EXPECT_NE(star_groups[far], star_groups[first_in(0)]);
}

TEST(ImproveInParts, FrozenNodesNeitherMoveNorLoseTheirFaces)
{
    const InterfaceComplex complex = two_spheres();
    const TetMesh mesh = tetrahedralize(complex, {.max_volume_mm3 = 2, .improve = false});
    const detail::SurfaceReference reference(complex);
    // Every node frozen: no move, no flip of an interface edge, no split of an interface face.
    detail::WorkMesh work(mesh, std::vector<char>(mesh.vertices.size(), 1));
    std::size_t moves = 0, flips = 0, splits = 0;
    for (std::uint32_t v = 0; v < mesh.vertices.size(); ++v) {
        EXPECT_EQ(work.kind(v), detail::NodeKind::corner);
        moves += detail::smooth_node(work, v, reference, 1.0);
    }
    for (const Triangle& f : mesh.faces) {
        flips += detail::flip_interface_edge(work, f[0], f[1], reference, 1.0);
        const Vec3 centre = (1.0 / 3) * (mesh.vertices[f[0]] + mesh.vertices[f[1]] + mesh.vertices[f[2]]);
        splits += detail::split_simplex(work, {f[0], f[1], f[2]}, centre).has_value();
    }
    EXPECT_EQ(moves + flips + splits, 0u);
    // Unfrozen, the same mesh has nodes that move and faces that split (the checks above could fail).
    detail::WorkMesh free_mesh(mesh);
    std::size_t free_moves = 0, free_splits = 0;
    for (std::uint32_t v = 0; v < mesh.vertices.size() && free_moves == 0; ++v)
        free_moves += detail::smooth_node(free_mesh, v, reference, 1.0);
    for (const Triangle& f : mesh.faces) {
        const Vec3 centre = (1.0 / 3) * (mesh.vertices[f[0]] + mesh.vertices[f[1]] + mesh.vertices[f[2]]);
        if (detail::split_simplex(free_mesh, {f[0], f[1], f[2]}, centre)) {
            ++free_splits;
            break;
        }
    }
    EXPECT_GT(free_moves, 0u);
    EXPECT_GT(free_splits, 0u);
}

TEST(ImproveInParts, KeepTheInvariantsAndTheBytesWhateverTheThreads)
{
    const InterfaceComplex complex = two_spheres();
    const TetMesh start = tetrahedralize(complex, {.max_volume_mm3 = 1, .improve = false});
    const auto before_volumes = volumes(start);
    const int threads = omp_get_max_threads();
    TetMesh one = start, two = start;
    omp_set_num_threads(1);
    const ImproveReport report = improve_mesh(one, complex, {.parts = 4});
    omp_set_num_threads(2);
    improve_mesh(two, complex, {.parts = 4});
    omp_set_num_threads(threads);
    EXPECT_EQ(one.vertices, two.vertices);
    EXPECT_EQ(one.tets, two.tets);
    EXPECT_EQ(one.tet_labels, two.tet_labels);
    EXPECT_EQ(one.faces, two.faces);
    expect_valid(one);
    expect_angles_raised("two spheres in 4 parts", report);
    const InterfaceDistance distance = interface_distance(one, complex);
    EXPECT_LT(distance.max_node_mm, 1e-9);
    EXPECT_EQ(distance.unmatched_faces, 0u);
    const auto after_volumes = volumes(one);
    for (const auto& [label, v] : before_volumes)
        EXPECT_NEAR(after_volumes.at(label), v, 1e-3 * v) << "tissue " << label;
    // The parts did work the serial run does: the figures are alike.
    TetMesh whole = start;
    const ImproveReport serial = improve_mesh(whole, complex, {.parts = 1});
    EXPECT_NEAR(report.after.p1_min_dihedral_deg, serial.after.p1_min_dihedral_deg, 1.0);
}

} // namespace
} // namespace tissuemesh::volume

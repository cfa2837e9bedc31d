// Contraction before the collapses (DecimateOptions::contract_block_mm, LocalEditor::try_contract): the patch
// vertices of a cube joined by edges become one, judged once as a collapse is. Only a disc may be contracted, the
// result stays a valid complex within the distance bound, and the decimation ends about as coarse.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>

#include "core/error.h"
#include "image/phantom.h"
#include "surface/check_complex.h"
#include "surface/decimate.h"
#include "surface/detail/local_editor.h"
#include "surface/extract_interfaces.h"
#include "surface/smooth.h"
#include "tests/support/phantom_distance.h"

namespace tissuemesh {
namespace {

using surface::detail::LocalEditor;
using surface::detail::VertexKind;

InterfaceComplex smoothed(const image::Phantom& phantom)
{
    InterfaceComplex complex = surface::extract_interfaces(phantom.image);
    surface::smooth(complex, phantom.image);
    return complex;
}

/// A patch vertex whose neighbours are all patch vertices of its own patch, and those neighbours (ascending).
std::pair<std::uint32_t, std::vector<std::uint32_t>> inner_patch_vertex(const LocalEditor& editor)
{
    for (std::uint32_t v = 0; v < editor.vertex_slots(); ++v) {
        if (!editor.vertex_alive(v) || editor.kind(v) != VertexKind::patch) continue;
        const std::vector<std::uint32_t> ring = editor.neighbours(v);
        if (ring.size() == 6 && std::all_of(ring.begin(), ring.end(), [&](std::uint32_t w) {
                return editor.kind(w) == VertexKind::patch && editor.neighbours(w).size() == 6;
            }))
            return {v, ring};
    }
    return {0, {}};
}

TEST(LocalEditorContract, AVertexAndItsRingBecomeAFanOverTheRing)
{
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = 4.0});
    LocalEditor editor(smoothed(phantom), {.min_angle_deg = 1, .max_tilt_deg = 60, .min_gap_mm = 0.1}, 8.0);
    const auto [v, ring] = inner_patch_vertex(editor);
    ASSERT_EQ(ring.size(), 6u);
    std::vector<std::uint32_t> cluster = ring;
    cluster.push_back(v);
    std::sort(cluster.begin(), cluster.end());
    const std::size_t before = editor.triangle_count();
    const Vec3 at = editor.position(v);
    ASSERT_TRUE(editor.try_contract(cluster, v));
    // Seven vertices become one: 6 removed, 12 triangles fewer (a disc of 7 inner vertices to a fan of its rim).
    EXPECT_EQ(editor.triangle_count(), before - 12);
    EXPECT_EQ(editor.position(v), at); // the kept vertex stays where it was
    for (const std::uint32_t w : ring) EXPECT_FALSE(editor.vertex_alive(w));
    EXPECT_EQ(editor.kind(v), VertexKind::patch);
    const surface::CheckReport check = surface::check_complex(editor.result());
    EXPECT_TRUE(check.ok()) << (check.first_error() ? check.first_error()->description : "");
}

TEST(LocalEditorContract, ARingWithoutItsCentreIsNoDiscAndIsRefused)
{
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = 4.0});
    LocalEditor editor(smoothed(phantom), {.min_angle_deg = 1, .max_tilt_deg = 60, .min_gap_mm = 0.1}, 8.0);
    const auto [v, ring] = inner_patch_vertex(editor);
    ASSERT_EQ(ring.size(), 6u);
    const std::size_t before = editor.triangle_count();
    // The ring's triangles hold the centre too, which would be left inside the fan: an annulus, not a disc.
    EXPECT_FALSE(editor.try_contract(ring, ring.front()));
    // A representative outside the cluster, or a cluster of one, is no contraction either.
    EXPECT_FALSE(editor.try_contract({ring.front(), ring.back()}, v));
    EXPECT_FALSE(editor.try_contract({v}, v));
    EXPECT_EQ(editor.triangle_count(), before);
    EXPECT_TRUE(editor.vertex_alive(v));
    for (const std::uint32_t w : ring) EXPECT_TRUE(editor.vertex_alive(w));
    EXPECT_TRUE(surface::check_complex(editor.result()).ok());
}

TEST(LocalEditorContract, AVetoLeavesTheComplexAsItWas)
{
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = 4.0});
    const InterfaceComplex input = smoothed(phantom);
    LocalEditor editor(input, {.min_angle_deg = 1, .max_tilt_deg = 60, .min_gap_mm = 0.1}, 8.0);
    const auto [v, ring] = inner_patch_vertex(editor);
    ASSERT_EQ(ring.size(), 6u);
    std::vector<std::uint32_t> cluster = ring;
    cluster.push_back(v);
    std::sort(cluster.begin(), cluster.end());
    bool asked = false;
    EXPECT_FALSE(editor.try_contract(cluster, v, [&] { return asked = true, false; }));
    EXPECT_TRUE(asked);
    const InterfaceComplex after = editor.result(), untouched = LocalEditor(input, {}, 8.0).result();
    EXPECT_EQ(after.triangles, untouched.triangles);
    EXPECT_EQ(after.vertices, untouched.vertices);
}

struct Run {
    InterfaceComplex complex;
    surface::DecimateReport report;
    surface::CheckReport check;
    testing::DistanceFigures distances;
};

Run decimate_with(const image::Phantom& phantom, const InterfaceComplex& input, double block_mm, std::size_t slabs)
{
    Run run{input, {}, {}, {}};
    run.report = surface::decimate(run.complex, {.max_distance_mm = 0.5,
                                                 .max_edge_mm = 4 * phantom.image.spacing_mm()[0],
                                                 .max_normal_change_deg = 45,
                                                 .contract_block_mm = block_mm,
                                                 .slabs = slabs});
    run.check = surface::check_complex(run.complex);
    run.distances = testing::phantom_distances(phantom, run.complex);
    return run;
}

void check_contraction(const std::string& name, double voxel_mm, std::size_t slabs)
{
    const image::Phantom phantom = image::make_phantom(name, {.voxel_mm = voxel_mm});
    const InterfaceComplex input = smoothed(phantom);
    const surface::CheckReport before = surface::check_complex(input);
    ASSERT_TRUE(before.ok());
    const Run plain = decimate_with(phantom, input, 0, slabs);
    const Run contracted = decimate_with(phantom, input, 1.5 * voxel_mm, slabs);
    std::cout << "[ figures  ] " << name << " at " << voxel_mm << " mm, " << slabs
              << " slab(s): " << input.triangle_count() << " -> " << plain.report.triangles_after << " triangles by "
              << plain.report.collapses << " collapses (" << plain.distances.max_voxels << "/"
              << plain.distances.mean_voxels << " voxel from the exact interfaces); with contraction "
              << contracted.report.contractions << " contractions of " << contracted.report.contracted_vertices
              << " vertices (" << contracted.report.contractions_refused << " refused), " << contracted.report.collapses
              << " collapses -> " << contracted.report.triangles_after << " (" << contracted.distances.max_voxels << "/"
              << contracted.distances.mean_voxels << " voxel)\n";
    EXPECT_EQ(plain.report.contractions, 0u);
    EXPECT_GT(contracted.report.contractions, 0u);
    EXPECT_GT(contracted.report.contracted_vertices, contracted.report.contractions);
    EXPECT_TRUE(contracted.check.ok()) << (contracted.check.first_error() ? contracted.check.first_error()->description
                                                                          : "");
    EXPECT_LE(contracted.report.max_distance_mm, 0.5);
    // As coarse within 10%, and as close to the exact interfaces as the bound allows.
    EXPECT_NEAR(static_cast<double>(contracted.report.triangles_after),
                static_cast<double>(plain.report.triangles_after),
                0.1 * static_cast<double>(plain.report.triangles_after));
    EXPECT_LE(contracted.distances.max_voxels, plain.distances.max_voxels + 0.1);
    EXPECT_LE(contracted.distances.mean_voxels, plain.distances.mean_voxels + 0.02);
    ASSERT_EQ(contracted.check.tissues.size(), before.tissues.size());
    // Tissue volumes move about as much as the collapses alone move them (within 1% of the volume more).
    for (const auto& [tissue, facts] : before.tissues) {
        const surface::TissueCheck& now = contracted.check.tissues.at(tissue);
        const double plain_change = std::abs(plain.check.tissues.at(tissue).volume_mm3 - facts.volume_mm3);
        std::cout << "[ figures  ] tissue " << tissue << ": " << facts.volume_mm3 << " mm^3 -> "
                  << plain.check.tissues.at(tissue).volume_mm3 << " by collapses, " << now.volume_mm3
                  << " with contraction\n";
        EXPECT_EQ(now.components, facts.components) << "tissue " << tissue;
        EXPECT_LE(std::abs(now.volume_mm3 - facts.volume_mm3), plain_change + 0.01 * std::abs(facts.volume_mm3))
            << "tissue " << tissue;
    }
}

TEST(DecimateContract, SpheresStayValidWithinTheBound) { check_contraction("spheres4", 4.0, 1); }

TEST(DecimateContract, JunctionCurvesStayInSlabs) { check_contraction("junction", 1.0, 4); }

TEST(DecimateContract, TheOneVoxelShellStaysOnePiece) { check_contraction("thin", 1.0, 3); }

TEST(DecimateContract, RejectsBadOptions)
{
    InterfaceComplex complex = smoothed(image::make_phantom("boxes", {.voxel_mm = 4.0}));
    EXPECT_THROW(surface::decimate(complex, {.contract_block_mm = -1}), InputError);
    EXPECT_THROW(
        surface::decimate(complex, {.mode = surface::DecimateMode::size, .target_edge_mm = 4, .contract_block_mm = 4}),
        InputError);
}

} // namespace
} // namespace tissuemesh

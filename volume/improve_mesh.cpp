#include "volume/improve_mesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <exception>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include "core/error.h"
#include "core/tet_shape.h"
#include "surface/detail/cgal_intersections.h"
#include "surface/detail/voxel_sides.h"
#include "volume/check_mesh.h"
#include "volume/detail/improver.h"
#include "volume/detail/mesh_parts.h"
#include "volume/detail/tet_quality.h"
#include "volume/detail/surface_reference.h"

namespace tissuemesh::volume {
namespace {

void validate(const TetMesh& mesh, const ImproveOptions& options)
{
    validate_indices(mesh, "mesh");
    if (!(options.target_dihedral_deg > 0 && options.target_dihedral_deg <= 70))
        throw InputError(concat("target dihedral angle ", options.target_dihedral_deg,
                                " deg is outside (0, 70]; a regular "
                                "tetrahedron has 70.5 deg; the default is 21"));
    if (!(options.max_face_deviation >= 0 && options.max_face_deviation <= 1))
        throw InputError(concat("face deviation ", options.max_face_deviation,
                                " is outside [0, 1]; it is a fraction of the "
                                "reference surface's mean edge (0.03 is the default)"));
    if (!(options.max_volume_change >= 0 && options.max_volume_change <= 1))
        throw InputError(concat("volume change ", options.max_volume_change,
                                " is outside [0, 1]; it is a fraction of each "
                                "tissue's volume (2e-4 is the default)"));
    if (options.parts > 64)
        throw InputError(
            concat(options.parts, " mesh parts is more than the 64 allowed; give 0 (chosen by size) .. 64"));
    if (!(options.max_tet_volume_mm3 >= 0 && std::isfinite(options.max_tet_volume_mm3)))
        throw InputError(
            concat("tet volume bound ", options.max_tet_volume_mm3, " mm^3 is not a finite number >= 0 (0: no bound)"));
    if (options.voxel_image != nullptr && !mesh.vertices.empty()) {
        // A mesh beside the image would be judged against no voxel, or the wrong ones: every edit allowed, silently.
        const auto [low, high] = options.voxel_image->world_bounds_mm();
        Vec3 mesh_low = mesh.vertices.front(), mesh_high = mesh_low;
        for (const Vec3& p : mesh.vertices)
            for (int a = 0; a < 3; ++a)
                mesh_low[a] = std::min(mesh_low[a], p[a]), mesh_high[a] = std::max(mesh_high[a], p[a]);
        double beyond = 0;
        for (int a = 0; a < 3; ++a) beyond = std::max({beyond, low[a] - mesh_low[a], mesh_high[a] - high[a]});
        const Vec3 spacing = options.voxel_image->spacing_mm();
        if (beyond > 2 * std::max({spacing[0], spacing[1], spacing[2]}))
            throw InputError(concat("the mesh reaches ", format_mm(beyond, 1),
                                    " mm beyond the voxel image's box; give the label image its surfaces were made "
                                    "from (the workflow's clean.nii.gz)"));
    }
    for (const auto& [tissue, bound] : options.max_tet_volume_per_tissue_mm3)
        if (!(bound > 0 && std::isfinite(bound)))
            throw InputError(concat("tet volume bound ", bound, " mm^3 for tissue ", tissue,
                                    " is not a finite "
                                    "positive number"));
}

/// Adds what one part's improvement did to the report of the whole.
void add_counts(ImproveReport& whole, const ImproveReport& part)
{
    whole.smoothed_nodes += part.smoothed_nodes;
    whole.edges_removed += part.edges_removed;
    whole.faces_removed += part.faces_removed;
    whole.interface_edges_flipped += part.interface_edges_flipped;
    whole.nodes_inserted += part.nodes_inserted;
    whole.nodes_inserted_on_interfaces += part.nodes_inserted_on_interfaces;
    whole.refused_by_voxels += part.refused_by_voxels;
    whole.refused_crossing_boundary += part.refused_crossing_boundary;
    whole.passes = std::max(whole.passes, part.passes);
}

/// Per tissue, the volume of its tets (mm^3).
std::map<Label, double> tissue_volumes(const TetMesh& mesh)
{
    std::map<Label, double> volumes;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) volumes[mesh.tet_labels[t]] += signed_volume(mesh, t);
    return volumes;
}

/// Improves the parts of `mesh` (part_of per tet, `count` parts) side by side, each with the nodes on the faces
/// it shares with the rest frozen, and puts them back; flags those nodes in `seam` (per node) when given. With `seeds`
/// (per node), a part works only from the tets at a flagged node. With `allowance` (mm^3 per tissue; one part only),
/// the part's tissue volumes may drift that far, else ImproveOptions::max_volume_change of their volumes in the part.
/// `last`: no round follows (detail::improve_in_place()).
void improve_parts(TetMesh& mesh, const std::vector<std::uint32_t>& part_of, std::size_t count,
                   const detail::SurfaceReference& reference, const surface::detail::VoxelSides* sides,
                   const ImproveOptions& options, const std::vector<char>& seeds, std::vector<char>* seam,
                   ImproveReport& report, const std::function<void()>& part_done,
                   const std::map<Label, double>& allowance = {}, bool last = false)
{
    const detail::PartCutter cutter(mesh);
    std::vector<std::vector<std::uint32_t>> tets(count);
    for (std::uint32_t t = 0; t < part_of.size(); ++t)
        if (part_of[t] != detail::no_part) tets[part_of[t]].push_back(t);
    std::vector<detail::MeshPart> parts(count);
    std::vector<TetMesh> edited(count);
    std::vector<ImproveReport> reports(count);
    std::exception_ptr failure;
#pragma omp parallel for schedule(dynamic, 1)
    for (std::size_t k = 0; k < count; ++k) {
        if (tets[k].empty()) continue;
        try {
            parts[k] = cutter.part(tets[k]);
            std::vector<char> local_seeds;
            if (!seeds.empty()) {
                local_seeds.assign(parts[k].from_node.size(), 0);
                for (std::size_t v = 0; v < local_seeds.size(); ++v)
                    local_seeds[v] = parts[k].from_node[v] < seeds.size() && seeds[parts[k].from_node[v]];
            }
            edited[k] = std::move(parts[k].mesh);
            detail::improve_in_place(edited[k], reference, sides, options, reports[k], parts[k].frozen,
                                     std::move(local_seeds), allowance, last);
        } catch (...) {
#pragma omp critical(improve_part_failure)
            if (!failure) failure = std::current_exception();
        }
#pragma omp critical(improve_part_done)
        part_done();
    }
    if (failure) std::rethrow_exception(failure);
    for (std::size_t k = 0; k < count; ++k) {
        add_counts(report, reports[k]);
        if (seam != nullptr)
            for (std::size_t v = 0; v < parts[k].from_node.size(); ++v)
                if (parts[k].frozen[v]) (*seam)[parts[k].from_node[v]] = 1;
    }
    mesh = detail::merge_parts(mesh, part_of, parts, edited);
}

/// Whether two of the mesh's listed faces on its outer boundary (a side whose tissue has no tet) cross (exact): the
/// safety net after the parts. 0.07 s on the 1 mm usc19-5 head, where testing every face with one tet, found by a face
/// adjacency of all the tets, took 0.34-0.46 s. tm-tetra's and tm-refine's meshes list every such face.
bool listed_outer_faces_cross(const TetMesh& mesh)
{
    std::set<Label> meshed(mesh.tet_labels.begin(), mesh.tet_labels.end());
    std::vector<std::uint32_t> outer;
    for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
        const LabelPair& sides = mesh.face_sides[f];
        const Triangle& c = mesh.faces[f];
        if ((!meshed.count(sides.from) || !meshed.count(sides.to)) &&
            !surface::detail::are_collinear(mesh.vertices[c[0]], mesh.vertices[c[1]], mesh.vertices[c[2]]))
            outer.push_back(f);
    }
    return !surface::detail::find_intersecting_pairs(mesh.vertices, mesh.faces, outer).empty();
}

/// How many parts improve_mesh() cuts `mesh` into.
std::size_t part_count(const TetMesh& mesh, const ImproveOptions& options)
{
    if (options.parts > 0) return options.parts;
    // An even number from two on, so that two cores finish their parts together: on the 1 mm usc19-5 head's
    // tm-tetra mesh (1.55 M tets) seven parts left one core idle for the seventh's second; six took 5.0-5.3 s
    // against seven's 5.7 (four: 5.2, eight: 5.3-5.8).
    // Two parts from 20 000 tets on, where one part left a core idle: the 1 mm sphere head's 334 k tets took 3.73 s
    // in one part and 1.98 s in two, the liver's 176 k 0.81 and 0.46 s, the `thin` phantom's 36 k 0.08 and 0.06 s.
    if (mesh.tets.size() < 20000) return 1;
    const std::size_t count = std::clamp<std::size_t>(mesh.tets.size() / 200000, 2, 8);
    return count - count % 2;
}

/// Rings of tets around the tets a band or the last round improves: room for their edits (edge rings, stars).
constexpr std::size_t band_rings = 2;

/// The smallest dihedral sine of tet t.
double min_sine_of(const TetMesh& mesh, std::size_t t)
{
    const Tet& tet = mesh.tets[t];
    return detail::min_sine(
        {mesh.vertices[tet[0]], mesh.vertices[tet[1]], mesh.vertices[tet[2]], mesh.vertices[tet[3]]});
}

/// Per node: whether a flagged tet holds it.
std::vector<char> nodes_of(const TetMesh& mesh, const std::vector<char>& tets)
{
    std::vector<char> nodes(mesh.vertices.size(), 0);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        if (tets[t])
            for (const std::uint32_t v : mesh.tets[t]) nodes[v] = 1;
    return nodes;
}

/// One more round around the tets still under the last round's bar after the parts and the bands
/// (detail::last_round_bar_deg(): 0.95 of the target while few are, else half of it): every tet within `band_rings`
/// rings of them, as one part. The bands can leave such a tet: on the 3 mm torso a 9.49-degree tet stayed,
/// which this round lifts to 12.66 degrees (with 2 to 6 rings alike), as does a second improver run. Nothing happens,
/// and nothing costs, when no tet is that low.
void improve_last_tets(TetMesh& mesh, const detail::SurfaceReference& reference,
                       const surface::detail::VoxelSides* sides, const ImproveOptions& options, ImproveReport& report)
{
    std::vector<double> sines(mesh.tets.size());
    std::size_t under = 0;
    const double rescue = detail::sine_of_deg(detail::rescue_fraction * options.target_dihedral_deg);
#pragma omp parallel for schedule(static) reduction(+ : under)
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        sines[t] = min_sine_of(mesh, t);
        under += sines[t] < rescue;
    }
    const double below =
        detail::sine_of_deg(detail::last_round_bar_deg(under, mesh.tets.size(), options.target_dihedral_deg));
    std::vector<char> seeds(mesh.tets.size(), 0);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) seeds[t] = sines[t] < below;
    if (std::find(seeds.begin(), seeds.end(), 1) == seeds.end()) return;
    const std::vector<char> start = nodes_of(mesh, seeds);
    const std::vector<char> around = detail::tets_around(mesh, seeds, band_rings);
    std::vector<std::uint32_t> part_of(mesh.tets.size(), detail::no_part);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        if (around[t]) part_of[t] = 0;
    // The round's tissue volumes may drift ImproveOptions::max_volume_change of the whole mesh's, not of the round's
    // own: its part is a few hundred tets, and held to its own volumes it can move almost nothing on an interface. In
    // the usc19-5 head resampled to 0.85 mm, a 0.16 mm^3 move of the air cavities' surface that lifts a 9.1-degree tet
    // was refused (0.014 mm^3 allowed, 2e-4 of the part's 69 mm^3; now 5.9 mm^3, 2e-4 of the whole's). With the
    // parts' and the bands' rounds, each tissue's volume drifts at most three times max_volume_change (0.06%).
    std::map<Label, double> allowance;
    for (const auto& [label, volume] : tissue_volumes(mesh))
        allowance[label] = options.max_volume_change * std::abs(volume);
    improve_parts(
        mesh, part_of, 1, reference, sides, options, start, nullptr, report, [] {}, allowance, true);
}

/// Improves the mesh in parts across it, then in bands around the faces between them (ImproveOptions::parts).
void improve_in_parts(TetMesh& mesh, const detail::SurfaceReference& reference,
                      const surface::detail::VoxelSides* sides, const ImproveOptions& options, std::size_t count,
                      ImproveReport& report, const Progress& progress)
{
    const detail::Cut cut = detail::cut_across(mesh, count);
    std::vector<char> seam(mesh.vertices.size(), 0);
    std::size_t done = 0;
    improve_parts(mesh, cut.part_of, count, reference, sides, options, {}, &seam, report,
                  [&] { progress.update("improve", 0.8 * static_cast<double>(++done) / static_cast<double>(count)); });
    // Then around the tets near those nodes (within two rings of tets) still below the target, and any tet still
    // below half the target, with two rings of tets beyond them for the edits' room (edge rings, smoothing stars).
    // Near, not only at: a tet a ring or two from the seam may need an edit that reaches a frozen node (an edge's
    // ring, a node's star), which its part refused (on the 1 mm usc19-5 head's refined mesh, tets of 3.07 and 4.77
    // degrees 6.5-6.7 mm from a cut, 2-3 tets, stayed so).
    const double target = detail::sine_of_deg(options.target_dihedral_deg);
    const double far_target = detail::sine_of_deg(detail::waiver_fraction * options.target_dihedral_deg);
    std::vector<char> at_seam(mesh.tets.size(), 0);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& tet = mesh.tets[t];
        at_seam[t] = std::any_of(tet.begin(), tet.end(), [&](std::uint32_t v) { return v < seam.size() && seam[v]; });
    }
    const detail::TetsAtNodes tets_at(mesh);
    std::vector<char> seeds = tets_at.around(at_seam, 2);
#pragma omp parallel for schedule(static)
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        seeds[t] = min_sine_of(mesh, t) < (seeds[t] ? target : far_target);
    const std::vector<char> around = tets_at.around(seeds, band_rings);
    // The bands' improvers start from the nodes of those tets (the seam's own nodes alone would leave them).
    const std::vector<char> start = nodes_of(mesh, seeds);
    const std::size_t bands = cut.between.size();
    // The tets at those nodes go in groups (joined through those nodes), each group whole to the band of the cut
    // nearest its first tet, so that no band freezes a node of a tet it is to improve: a tet midway between two cuts
    // otherwise saw its neighbours split between two bands and its nodes frozen in both. The outer ring goes to the
    // cut nearest each tet. (Groups joined through any node spanned the whole head: one band of 1.0 M tets.)
    std::vector<std::uint32_t> band_of = detail::groups_of(mesh, tets_at.around(seeds, 1), start);
    for (std::uint32_t t = 0; t < mesh.tets.size(); ++t) {
        // A group's root is its lowest tet, so it has its band already when its other tets come.
        if (band_of[t] != detail::no_part) band_of[t] = band_of[t] == t ? cut.nearest(mesh, t) : band_of[band_of[t]];
        else if (around[t]) band_of[t] = cut.nearest(mesh, t);
    }
    done = 0;
    improve_parts(mesh, band_of, bands, reference, sides, options, start, nullptr, report, [&] {
        progress.update("improve", 0.8 + 0.2 * static_cast<double>(++done) / static_cast<double>(bands));
    });
    report.parts = count;
    report.bands = bands;
    improve_last_tets(mesh, reference, sides, options, report);
}

/// Builds the reference with `make_reference` (or takes it, when it returns one made before) and improves `mesh`
/// against it, timing both.
template <class MakeReference>
ImproveReport run(TetMesh& mesh, MakeReference make_reference, const ImproveOptions& options, const Progress& progress)
{
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    const detail::SurfaceReference& reference = make_reference();
    std::optional<surface::detail::VoxelSides> sides;
    if (options.voxel_image != nullptr) sides.emplace(*options.voxel_image); // flags built once, for every part
    const surface::detail::VoxelSides* voxel_sides = sides ? &*sides : nullptr;
    ImproveReport report;
    report.before = shape_figures(mesh);
    if (const std::size_t count = part_count(mesh, options); count > 1) {
        // Each part, band and last round keeps the outer boundary it holds from crossing itself
        // (detail/outer_boundary.h), not from crossing the boundary another part holds. Should the parts' boundaries
        // meet (no mesh measured did), the whole mesh is improved again at once, where every edit is judged against
        // the whole boundary. (A mesh given crossed keeps the parts' result: improving it whole would not mend that.)
        const TetMesh unimproved = mesh;
        improve_in_parts(mesh, reference, voxel_sides, options, count, report, progress);
        if (listed_outer_faces_cross(mesh) && !listed_outer_faces_cross(unimproved)) {
            progress.info("improve", "the parts' outer boundaries crossed each other; improving the mesh again as one "
                                     "part");
            mesh = unimproved;
            const ShapeFigures before = report.before;
            report = {};
            report.before = before;
            detail::improve_in_place(mesh, reference, voxel_sides, options, report, {}, {}, {}, true, progress);
        }
    } else {
        detail::improve_in_place(mesh, reference, voxel_sides, options, report, {}, {}, {}, true, progress);
    }
    report.after = shape_figures(mesh);
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report.cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    return report;
}

} // namespace

ShapeFigures shape_figures(const TetMesh& mesh)
{
    ShapeFigures figures;
    figures.tets = mesh.tets.size();
    if (mesh.tets.empty()) return figures;
    std::vector<double> smallest(mesh.tets.size()), largest(mesh.tets.size());
#pragma omp parallel for schedule(static)
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        std::tie(smallest[t], largest[t]) = dihedral_range_deg(mesh, t);
    }
    figures.min_dihedral_deg = *std::min_element(smallest.begin(), smallest.end());
    figures.max_dihedral_deg = *std::max_element(largest.begin(), largest.end());
    for (const double angle : smallest)
        figures.tets_under_10_deg += angle < 10, figures.tets_under_20_deg += angle < 20;
    const auto nth = smallest.begin() + static_cast<std::ptrdiff_t>(smallest.size() / 100);
    std::nth_element(smallest.begin(), nth, smallest.end());
    figures.p1_min_dihedral_deg = *nth;
    return figures;
}

ImproveReport improve_mesh(TetMesh& mesh, const InterfaceComplex& surface, const ImproveOptions& options,
                           const Progress& progress)
{
    validate(mesh, options);
    return run(
        mesh, [&] { return detail::SurfaceReference(surface); }, options, progress);
}

ImproveReport improve_mesh(TetMesh& mesh, const ImproveOptions& options, const Progress& progress)
{
    validate(mesh, options);
    return run(
        mesh, [&] { return detail::SurfaceReference(mesh.vertices, mesh.faces, mesh.face_sides); }, options, progress);
}

namespace detail {

ImproveReport improve_mesh_against(TetMesh& mesh, const SurfaceReference& reference, const ImproveOptions& options,
                                   const Progress& progress)
{
    validate(mesh, options);
    return run(
        mesh, [&]() -> const SurfaceReference& { return reference; }, options, progress);
}

} // namespace detail

} // namespace tissuemesh::volume

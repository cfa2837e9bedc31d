#include "surface/repair.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <set>

#include "core/error.h"
#include "surface/check_complex.h"
#include "surface/detail/complex_editor.h"
#include "surface/detail/mesh_measures.h"
#include "surface/detail/repair_contacts.h"
#include "surface/detail/repair_log.h"

namespace tissuemesh::surface {
namespace {

using detail::RepairLog;

Vec3 centroid(const InterfaceComplex& complex, const Triangle& t)
{
    return (1.0 / 3.0) * (complex.vertices[t[0]] + complex.vertices[t[1]] + complex.vertices[t[2]]);
}

/// Maps every used vertex to the lowest index at the same coordinates (as check_complex() merges them).
void merge_coincident_vertices(InterfaceComplex& complex, RepairLog& log)
{
    std::vector<char> used(complex.vertices.size(), 0);
    for (const Triangle& t : complex.triangles)
        for (const std::uint32_t v : t) used[v] = 1;
    std::vector<std::uint32_t> order;
    for (std::uint32_t v = 0; v < used.size(); ++v)
        if (used[v]) order.push_back(v);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        return complex.vertices[a] != complex.vertices[b] ? complex.vertices[a] < complex.vertices[b] : a < b;
    });
    std::vector<std::uint32_t> canonical(complex.vertices.size());
    std::iota(canonical.begin(), canonical.end(), 0u);
    for (std::size_t i = 1; i < order.size(); ++i) {
        const std::uint32_t keep = canonical[order[i - 1]], v = order[i];
        if (complex.vertices[v] != complex.vertices[keep]) continue;
        canonical[v] = keep;
        ++log.report().merged_vertices;
        log.add(RepairKind::merged_vertex, complex.vertices[v], {}, concat("merged vertex ", v, " into vertex ", keep));
    }
    for (Triangle& t : complex.triangles)
        for (std::uint32_t& v : t) v = canonical[v];
}

void erase_marked(InterfaceComplex& complex, const std::vector<char>& drop)
{
    std::size_t kept = 0;
    for (std::size_t t = 0; t < complex.triangles.size(); ++t) {
        if (drop[t]) continue;
        complex.triangles[kept] = complex.triangles[t];
        complex.sides[kept++] = complex.sides[t];
    }
    complex.triangles.resize(kept);
    complex.sides.resize(kept);
}

/// The triangle in its patch's canonical form: wound so that the smaller label is `from`, then rotated
/// to start at its smallest vertex index. Equal keys: the same interface triangle.
std::pair<std::pair<Label, Label>, Triangle> oriented_key(const Triangle& t, const LabelPair& side)
{
    Triangle w = side.from < side.to ? t : Triangle{t[0], t[2], t[1]};
    std::rotate(w.begin(), std::min_element(w.begin(), w.end()), w.end());
    return {std::minmax(side.from, side.to), w};
}

/// Drops triangles with a repeated vertex (no area, no tissue behind them) and exact repeats of another
/// triangle (same vertices, tissues and side). Doubles that disagree (other tissues, or the same tissues
/// wound the other way) are ambiguous and stay for the final check to report.
void drop_degenerate_and_repeated(InterfaceComplex& complex, RepairLog& log)
{
    std::vector<char> drop(complex.triangles.size(), 0);
    std::set<std::pair<std::pair<Label, Label>, Triangle>> seen;
    for (std::size_t i = 0; i < complex.triangles.size(); ++i) {
        const Triangle& t = complex.triangles[i];
        const LabelPair& side = complex.sides[i];
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
            drop[i] = 1;
            ++log.report().removed_degenerate;
            log.add(RepairKind::removed_degenerate, centroid(complex, t), {side.from, side.to},
                    concat("dropped ", log.patch(side), " triangle ", i, " (repeated vertex, zero area)"));
        } else if (!seen.insert(oriented_key(t, side)).second) {
            drop[i] = 1;
            ++log.report().removed_duplicates;
            log.add(RepairKind::removed_duplicate, centroid(complex, t), {side.from, side.to},
                    concat("dropped ", log.patch(side), " triangle ", i, " (a repeat of another)"));
        }
    }
    erase_marked(complex, drop);
}

/// Turns triangles wound against the majority of their neighbours across edges of their own patch
/// (edges the patch uses exactly twice); a few passes settle small flipped groups.
void turn_flipped_triangles(InterfaceComplex& complex, RepairLog& log)
{
    for (int pass = 0; pass < 8; ++pass) {
        // Directed edges in each patch's canonical winding: (patch, min, max) -> (triangle, forward).
        std::map<std::tuple<Label, Label, std::uint32_t, std::uint32_t>, std::vector<std::pair<std::uint32_t, bool>>>
            edges;
        for (std::uint32_t i = 0; i < complex.triangles.size(); ++i) {
            const auto [patch, w] = oriented_key(complex.triangles[i], complex.sides[i]);
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t a = w[k], b = w[(k + 1) % 3];
                edges[{patch.first, patch.second, std::min(a, b), std::max(a, b)}].emplace_back(i, a < b);
            }
        }
        std::vector<int> agree(complex.triangles.size(), 0), disagree(complex.triangles.size(), 0);
        for (const auto& [edge, users] : edges) {
            if (users.size() != 2) continue;
            auto& tally = users[0].second != users[1].second ? agree : disagree;
            ++tally[users[0].first];
            ++tally[users[1].first];
        }
        std::size_t turned = 0;
        for (std::uint32_t i = 0; i < complex.triangles.size(); ++i) {
            if (disagree[i] <= agree[i]) continue;
            std::swap(complex.triangles[i][1], complex.triangles[i][2]);
            ++turned;
            ++log.report().flipped_triangles;
            log.add(RepairKind::flipped_triangle, centroid(complex, complex.triangles[i]),
                    {complex.sides[i].from, complex.sides[i].to},
                    concat("turned ", log.patch(complex.sides[i]), " triangle ", i, " (wound against ", disagree[i],
                           " of its ", agree[i] + disagree[i], " neighbours)"));
        }
        if (turned == 0) return;
    }
}

std::set<Label> tissues_of(const InterfaceComplex& complex)
{
    std::set<Label> tissues;
    for (const LabelPair& side : complex.sides) tissues.insert({side.from, side.to});
    return tissues;
}

/// Refuses defects no local edit can fix (holes, a tissue touching itself, ambiguous doubles), before editing.
void require_repairable(const InterfaceComplex& complex, const std::string& when)
{
    const CheckReport check = check_complex(complex, {.max_defects_per_kind = 1, .check_intersections = false});
    for (const DefectKind kind :
         {DefectKind::open_edge, DefectKind::orientation_conflict, DefectKind::non_manifold_edge,
          DefectKind::duplicate_triangle, DefectKind::duplicate_vertex}) {
        if (check.count(kind) == 0) continue;
        const auto found =
            std::find_if(check.defects.begin(), check.defects.end(), [&](const Defect& d) { return d.kind == kind; });
        throw AlgorithmError(
            concat("repair: ", check.count(kind), ' ', to_string(kind), " defect", check.count(kind) == 1 ? "" : "s",
                   ' ', when, ", first: ", found != check.defects.end() ? found->description : "?",
                   "; repair fixes only unambiguous defects and never changes the topology: re-extract the "
                   "interfaces from the label image with tm-extract"));
    }
}

} // namespace

std::string to_string(RepairKind kind)
{
    switch (kind) {
    case RepairKind::merged_vertex: return "merged-vertex";
    case RepairKind::removed_duplicate: return "removed-duplicate";
    case RepairKind::removed_degenerate: return "removed-degenerate";
    case RepairKind::collapsed_degenerate: return "collapsed-degenerate";
    case RepairKind::flipped_triangle: return "flipped-triangle";
    case RepairKind::intersection: return "intersection";
    case RepairKind::near_contact: return "near-contact";
    }
    return "?";
}

bool RepairReport::changed() const
{
    return merged_vertices + removed_duplicates + removed_degenerate + collapsed_degenerate + flipped_triangles +
               moved_vertices >
           0;
}

RepairReport repair(InterfaceComplex& complex, const RepairOptions& options, const LabelImage* image,
                    const Progress& progress)
{
    validate_indices(complex, "repair input");
    if (!(options.gap_mm >= 0)) throw InputError(concat("repair: gap ", options.gap_mm, " mm must not be negative"));
    if (!(options.max_depth_voxels > 0 && options.max_depth_voxels <= 1))
        throw InputError(concat("repair: max depth ", options.max_depth_voxels, " voxels is outside (0, 1]"));
    if (complex.triangles.empty())
        throw InputError("repair: the interface complex has no triangle; extract the interfaces first (tm-extract)");
    RepairReport report;
    report.triangles_before = complex.triangle_count();
    RepairLog log(complex.names, options.max_actions, report);
    const std::set<Label> tissues = tissues_of(complex);

    merge_coincident_vertices(complex, log);
    drop_degenerate_and_repeated(complex, log);
    turn_flipped_triangles(complex, log);
    progress.update("repair", 0.1);
    require_repairable(complex, "remain after merging vertices, dropping repeats and turning flipped triangles");

    const double cell_mm = 2 * detail::mean_edge_length(complex);
    // Untangling crossings may pass through thin wedges at shared vertices on the way (a crossing is the
    // worse defect, and the moves never add one), so the wedge rule of the other steps is off here.
    detail::ComplexEditor editor(std::move(complex),
                                 {.min_angle_deg = 0,
                                  .max_normal_change_deg = 90,
                                  .min_gap_mm = 0,
                                  .min_wedge_deg = 0,
                                  .tolerate_existing_intersections = true},
                                 cell_mm);
    detail::collapse_degenerate_triangles(editor, log);
    detail::separate_surfaces(editor,
                              {.gap_mm = options.gap_mm,
                               .max_rounds = options.max_rounds,
                               .image = image,
                               .max_depth_voxels = options.max_depth_voxels},
                              log, progress);
    complex = editor.result();
    report.triangles_after = complex.triangle_count();

    const std::set<Label> now = tissues_of(complex);
    for (const Label tissue : tissues)
        if (!now.contains(tissue))
            throw AlgorithmError(concat("repair: tissue ", log.tissue(tissue),
                                        " would lose its last triangle; "
                                        "its surface is degenerate: re-extract the interfaces with tm-extract"));
    const CheckReport check = check_complex(complex, {.max_defects_per_kind = 1});
    if (!check.ok())
        throw AlgorithmError(concat("repair: ", check.error_count(), " defect", check.error_count() == 1 ? "" : "s",
                                    " remain after repair, first: ", check.first_error()->description,
                                    "; re-extract the interfaces from the label image with tm-extract"));
    progress.info("repair", concat(report.triangles_before, " -> ", report.triangles_after, " triangles; ",
                                   report.merged_vertices, " vertices merged, ", report.moved_vertices,
                                   " moved apart (at most ", format_mm(report.max_move_mm), " mm)"));
    return report;
}

} // namespace tissuemesh::surface

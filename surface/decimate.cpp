#include "surface/decimate.h"

#include <algorithm>
#include <chrono>
#include <limits>

#include "core/error.h"
#include "surface/detail/decimator.h"
#include "surface/detail/layer_sizing.h"
#include "surface/detail/mesh_measures.h"

namespace tissuemesh::surface {
namespace {

using detail::Carried;
using detail::Decimator;
using detail::Piece;
using detail::Quadric;
using detail::Slab;

void validate(const DecimateOptions& options)
{
    if (!(options.max_distance_mm > 0))
        throw InputError(concat("decimate: max distance ", options.max_distance_mm, " mm must be positive"));
    if (!(options.max_edge_mm >= 0))
        throw InputError(concat("decimate: max edge ", options.max_edge_mm, " mm must not be negative (0: no bound)"));
    if (!(options.max_normal_change_deg > 0 && options.max_normal_change_deg <= 180))
        throw InputError(
            concat("decimate: max normal change ", options.max_normal_change_deg, " deg is outside (0, 180]"));
    if (!(options.min_angle_deg >= 0 && options.min_angle_deg < 60))
        throw InputError(concat("decimate: min angle ", options.min_angle_deg, " deg is outside [0, 60)"));
    if (!(options.min_gap_mm >= 0)) throw InputError("decimate: min gap must not be negative");
    if (!(options.min_sector_deg >= 0 && options.min_sector_deg < 90))
        throw InputError(concat("decimate: min sector ", options.min_sector_deg, " deg is outside [0, 90)"));
    if (options.mode == DecimateMode::size && !(options.target_edge_mm > 0) && options.target_edge_mm_by_pair.empty())
        throw InputError("decimate: size mode needs a target edge length (target_edge_mm or per tissue pair)");
    if (options.mode == DecimateMode::size && options.max_edge_mm > 0)
        throw InputError(concat("decimate: a max edge (", options.max_edge_mm,
                                " mm) bounds curvature mode only; size "
                                "mode splits every edge longer than 4/3 of its target edge length anyway: drop the "
                                "max edge, or lower the target"));
    if (!(options.edge_per_thickness >= 0 && options.edge_per_thickness <= 100))
        throw InputError(concat("decimate: edge per thickness ", options.edge_per_thickness, " is outside [0, 100]"));
    if (options.edge_per_thickness > 0 && !(options.mode == DecimateMode::curvature && options.max_edge_mm > 0))
        throw InputError("decimate: an edge per thickness bounds the edges of curvature mode under a max edge; give "
                         "a max edge as well (tm-decimate --max-edge-mm)");
    if (!(options.contract_block_mm >= 0))
        throw InputError(
            concat("decimate: contraction block ", options.contract_block_mm, " mm must not be negative (0: off)"));
    if (options.contract_block_mm > 0 && options.mode != DecimateMode::curvature)
        throw InputError("decimate: contraction in blocks is a step of curvature mode; drop it in size mode");
    if (options.slabs > options.max_slabs)
        throw InputError(concat("decimate: ", options.slabs, " slabs is more than the ", options.max_slabs,
                                " allowed; give at most ", options.max_slabs, " (0: chosen by size)"));
    for (const auto& [pair, length] : options.target_edge_mm_by_pair)
        if (!(length > 0))
            throw InputError(concat("decimate: target edge length ", length, " mm for tissues ", pair.first, '|',
                                    pair.second, " must be positive"));
}

/// How many slabs to decimate side by side: options.slabs, or one per 400 000 triangles, at least two from
/// 50 000 triangles on and at most 8; one when a triangle count must stop the decimation (the count is global).
/// Two at least, so that two cores share a mid-sized complex too: the 2 mm usc19-5 head's 735 682 triangles took
/// 8.1 s in one slab, 5.0 s in two (as much CPU).
std::size_t piece_count(const InterfaceComplex& complex, const DecimateOptions& options)
{
    if (options.target_triangles > 0) return 1;
    if (options.slabs > 0) return options.slabs;
    const std::size_t triangles = complex.triangle_count();
    return std::clamp<std::size_t>(triangles / 400'000, triangles >= 50'000 ? 2 : 1, 8);
}

/// What a slab carries, numbered as the slab: the quadrics of its vertices and the samples of its
/// triangles. A sample that is no vertex of the slab's triangles (an input vertex collapsed away earlier,
/// answered for by a triangle that reaches into the slab) joins the slab as a vertex no triangle uses.
Carried slab_carried(const InterfaceComplex& complex, const Carried& carried, detail::SlabPiece& slab)
{
    constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> local(complex.vertices.size(), none);
    for (std::uint32_t v = 0; v < slab.from_vertex.size(); ++v) local[slab.from_vertex[v]] = v;
    Carried out{{}, std::vector<std::vector<std::uint32_t>>(slab.from_triangle.size())};
    for (std::size_t t = 0; t < slab.from_triangle.size(); ++t)
        for (const std::uint32_t s : carried.samples[slab.from_triangle[t]]) {
            if (local[s] == none) {
                local[s] = static_cast<std::uint32_t>(slab.from_vertex.size());
                slab.from_vertex.push_back(s);
                slab.complex.vertices.push_back(complex.vertices[s]);
            }
            out.samples[t].push_back(local[s]);
        }
    out.quadrics.resize(slab.from_vertex.size());
    for (std::size_t v = 0; v < slab.from_vertex.size(); ++v) out.quadrics[v] = carried.quadrics[slab.from_vertex[v]];
    return out;
}

/// Decimates the `slabs` of the complex on their own (in parallel), each fenced off from the others, and
/// puts them together: the complex (numbered as before, dead vertices kept) and what it carries, plus in
/// `seams` the vertices the fences held back, where the next pass starts. With `seeds` (sorted), each slab
/// starts from those only. The result does not depend on the thread count.
InterfaceComplex decimate_in_slabs(InterfaceComplex&& complex, Carried& carried, const std::vector<Slab>& slabs,
                                   const std::vector<std::uint32_t>* seeds, const DecimateOptions& options,
                                   const detail::LayerSizing& sizing, DecimateReport& report, const Progress& progress,
                                   std::vector<std::uint32_t>& seams, const Vec3& block_origin)
{
    const auto began = std::chrono::steady_clock::now();
    std::vector<Piece> pieces(slabs.size());
    // The first slabs take the progress bar to 0.8, the slabs over the seams to 0.9.
    const double progress_from = seeds ? 0.8 : 0, progress_span = seeds ? 0.1 : 0.8;
    detail::edit_slabs(
        complex, slabs, {},
        [&](std::size_t k, detail::SlabPiece& slab) {
            Carried local = slab_carried(complex, carried, slab);
            const double cell_mm = 2 * detail::mean_edge_length(slab.complex);
            Decimator decimator(std::move(slab.complex), std::move(local), cell_mm, options, sizing, pieces[k].report,
                                slabs[k]);
            std::vector<std::uint32_t> own_seeds;
            if (seeds)
                for (std::uint32_t v = 0; v < slab.from_vertex.size(); ++v)
                    if (std::binary_search(seeds->begin(), seeds->end(), slab.from_vertex[v])) own_seeds.push_back(v);
            if (!seeds && options.contract_block_mm > 0) decimator.contract_blocks(block_origin);
            decimator.collapse_all({}, seeds ? &own_seeds : nullptr);
            decimator.hand_over(slab.from_vertex, pieces[k]);
        },
        [&](std::size_t done) {
            progress.update("decimate", progress_from + progress_span * static_cast<double>(done) /
                                                            static_cast<double>(slabs.size()));
        });
    std::size_t samples_before = 0, samples_after = 0;
    for (const std::vector<std::uint32_t>& samples : carried.samples) samples_before += samples.size();
    InterfaceComplex whole;
    whole.vertices = std::move(complex.vertices);
    whole.names = std::move(complex.names);
    whole.background = complex.background;
    carried.samples.clear();
    for (Piece& piece : pieces) {
        for (std::size_t t = 0; t < piece.triangles.size(); ++t) {
            whole.add_triangle(piece.triangles[t], piece.sides[t]);
            samples_after += piece.samples[t].size();
            carried.samples.push_back(std::move(piece.samples[t]));
        }
        for (const auto& [v, quadric] : piece.quadrics) carried.quadrics[v] = quadric;
        seams.insert(seams.end(), piece.fenced.begin(), piece.fenced.end());
        report.collapses += piece.report.collapses;
        report.contractions += piece.report.contractions;
        report.contracted_vertices += piece.report.contracted_vertices;
        report.contractions_refused += piece.report.contractions_refused;
        report.refused_by_distance += piece.report.refused_by_distance;
        report.refused_by_length += piece.report.refused_by_length;
        report.refused_by_checks += piece.report.refused_by_checks;
        report.max_distance_mm = std::max(report.max_distance_mm, piece.report.max_distance_mm);
        detail::add_counters(report, {.topology = piece.report.refused_topology,
                                      .shape = piece.report.refused_shape,
                                      .normal = piece.report.refused_fold,
                                      .intersection = piece.report.refused_intersection,
                                      .gap = piece.report.refused_gap,
                                      .wedge = piece.report.refused_wedge});
    }
    // Every input vertex is answered for by exactly one triangle: a slab that lost or doubled one would
    // leave the distance bound unchecked there.
    if (samples_after != samples_before)
        throw AlgorithmError(concat("decimate: the slabs answer for ", samples_after, " input vertices instead of ",
                                    samples_before, " (internal error)"));
    std::sort(seams.begin(), seams.end());
    seams.erase(std::unique(seams.begin(), seams.end()), seams.end());
    progress.debug("decimate",
                   concat(slabs.size(), " slabs: ", report.triangles_before, " -> ", whole.triangle_count(),
                          " triangles, ", seams.size(), " vertices held back at the seams (",
                          format_mm(std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count(), 1),
                          " s)"));
    return whole;
}

} // namespace

DecimateReport decimate(InterfaceComplex& complex, const DecimateOptions& options, const Progress& progress)
{
    validate(options);
    validate_indices(complex, "decimate input");
    DecimateReport report;
    report.triangles_before = complex.triangle_count();
    Carried carried = detail::initial_carried(complex);
    // Large complexes: slabs side by side first; then, from the vertices their fences held back, slabs cut
    // halfway between the first ones (each seam in the middle of one of them), again side by side; then one
    // pass over the whole from what those held back (measured on the 1 mm head in 8 slabs: the seams took a
    // serial pass of 14 s, a seventh of the whole).
    const std::size_t pieces = piece_count(complex, options);
    const detail::LayerSizing sizing(complex, complex.background,
                                     {.target_edge_mm = 0.75 * options.max_edge_mm,
                                      .edges_per_mm = options.edge_per_thickness,
                                      .min_edge_mm = 0.25 * options.max_edge_mm});
    // The contraction's blocks: one grid over the whole complex, whatever the slabs.
    Vec3 block_origin{0, 0, 0};
    if (!complex.vertices.empty()) {
        block_origin = complex.vertices.front();
        for (const Vec3& p : complex.vertices)
            for (int a = 0; a < 3; ++a) block_origin[a] = std::min(block_origin[a], p[a]);
    }
    std::vector<std::uint32_t> seams;
    if (pieces > 1) {
        const std::vector<Slab> slabs = detail::cut_into_slabs(complex, pieces);
        report.slabs = slabs.size();
        complex = decimate_in_slabs(std::move(complex), carried, slabs, nullptr, options, sizing, report, progress,
                                    seams, block_origin);
        if (const std::vector<Slab> between = detail::slabs_between(slabs); !between.empty()) {
            std::vector<std::uint32_t> left;
            complex = decimate_in_slabs(std::move(complex), carried, between, &seams, options, sizing, report, progress,
                                        left, block_origin);
            seams = std::move(left);
        }
    }
    const double cell_mm = 2 * detail::mean_edge_length(complex);
    Decimator decimator(std::move(complex), std::move(carried), cell_mm, options, sizing, report);
    if (pieces == 1 && options.contract_block_mm > 0) decimator.contract_blocks(block_origin);
    decimator.collapse_all(progress, pieces > 1 ? &seams : nullptr);
    if (options.mode == DecimateMode::size) decimator.split_long_edges();
    complex = decimator.result();
    detail::add_counters(report, decimator.editor().counters());
    report.triangles_after = complex.triangle_count();
    progress.info("decimate", concat(report.triangles_before, " -> ", report.triangles_after, " triangles; ",
                                     report.refused_by_distance, " collapses refused by the distance bound, ",
                                     report.refused_by_checks, " by the validity checks"));
    return report;
}

} // namespace tissuemesh::surface

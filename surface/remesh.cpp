#include "surface/remesh.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include "core/error.h"
#include "surface/detail/edge_fan.h"
#include "surface/detail/local_editor.h"
#include "surface/detail/mesh_measures.h"
#include "surface/detail/remesh_reference.h"
#include "surface/detail/slabs.h"
#include "surface/detail/voxel_sides.h"

namespace tissuemesh::surface {
namespace {

using detail::LocalEditor;
using detail::Reference;
using detail::Slab;
using detail::TriangleCorners;
using detail::unordered;
using detail::VertexKind;
using Edge = std::pair<std::uint32_t, std::uint32_t>;

void validate(const RemeshOptions& options)
{
    if (!(options.target_edge_mm > 0) && options.target_edge_mm_by_pair.empty())
        throw InputError("remesh: no target edge length; give target_edge_mm (tm-remesh --edge-mm) in mm");
    if (options.target_edge_mm < 0) throw InputError("remesh: the target edge length must be positive");
    for (const auto& [pair, length] : options.target_edge_mm_by_pair)
        if (!(length > 0))
            throw InputError(concat("remesh: target edge length ", length, " mm for tissues ", pair.first, '|',
                                    pair.second, " must be positive"));
    if (options.slabs > options.max_slabs)
        throw InputError(concat("remesh: ", options.slabs, " slabs is more than the ", options.max_slabs,
                                " allowed; give at most ", options.max_slabs, " (0: chosen by size)"));
    if (!(options.min_angle_deg >= 0 && options.min_angle_deg < 60))
        throw InputError(concat("remesh: min angle ", options.min_angle_deg, " deg is outside [0, 60)"));
    if (!(options.min_sector_deg >= 0 && options.min_sector_deg < 90))
        throw InputError(concat("remesh: min sector ", options.min_sector_deg, " deg is outside [0, 90)"));
    if (!(options.edge_per_thickness >= 0 && options.edge_per_thickness <= 100))
        throw InputError(concat("remesh: edge per thickness ", options.edge_per_thickness, " is outside [0, 100]"));
    if (!(options.min_relax_move >= 0 && options.min_relax_move < 1))
        throw InputError(
            concat("remesh: min relax move ", options.min_relax_move, " of the target edge is outside [0, 1)"));
    if (!(options.min_edge_mm >= 0 && options.min_edge_mm <= 1e6))
        throw InputError(concat("remesh: min edge ", options.min_edge_mm, " mm is outside [0, 1e6]"));
}

double smallest_angle_deg(const InterfaceComplex& complex)
{
    double smallest = 180;
    for (const Triangle& t : complex.triangles)
        smallest = std::min(smallest, detail::smallest_angle_deg(
                                          {complex.vertices[t[0]], complex.vertices[t[1]], complex.vertices[t[2]]}));
    return smallest;
}

class Remesher {
public:
    /// `reference`: the input surface, to project onto; `fence`: where edits may happen (nullopt: anywhere).
    /// `sides`: the voxels' sides to keep (RemeshOptions::voxel_image), or nullptr.
    Remesher(InterfaceComplex&& complex, const Reference& reference, const RemeshOptions& options, double cell_mm,
             RemeshReport& report, const detail::VoxelSides* sides,
             const std::optional<detail::EditFence>& fence = std::nullopt)
        : options_(options), report_(report), editor_(std::move(complex), detail::limits_of(options), cell_mm),
          reference_(reference), sides_(sides)
    {
        editor_.set_fence(fence);
    }

    void run(const Progress& progress)
    {
        for (std::size_t i = 0; i < options_.iterations; ++i) {
            split_long_edges();
            collapse_short_edges();
            editor_.rebuild_grid(2 * editor_.mean_edge_length());
            flip_towards_valence_six();
            flip_towards_delaunay();
            relax();
            progress.update("remesh", static_cast<double>(i + 1) / static_cast<double>(options_.iterations));
        }
        for (int pass = 0; pass < 3; ++pass) {
            remove_bad_triangles();
            flip_towards_delaunay();
        }
    }

    const LocalEditor& editor() const { return editor_; }

    void split_long_edges()
    {
        std::vector<std::pair<double, Edge>> long_edges;
        for (const Edge& e : edges())
            if (const double l = length(e); l > 4.0 / 3.0 * target(e.first, e.second)) long_edges.push_back({-l, e});
        std::sort(long_edges.begin(), long_edges.end());
        for (const auto& [l, e] : long_edges) {
            if (editor_.edge_multiplicity(e.first, e.second) == 0) continue;
            if (editor_.try_split(e.first, e.second, split_point(e.first, e.second))) ++report_.splits;
            else ++report_.refused;
        }
    }

private:
    /// Where edge ab splits: its midpoint, moved onto the input surface (its junction curves for a junction
    /// edge, else the patch of the edge's tissue pair), so new vertices start on the surface they stand for.
    Vec3 split_point(std::uint32_t a, std::uint32_t b) const
    {
        const Vec3 middle = 0.5 * (editor_.position(a) + editor_.position(b));
        const double reach = distance(editor_.position(a), editor_.position(b));
        if (editor_.edge_multiplicity(a, b) >= 3) return reference_.onto_curve(middle, reach);
        for (const std::uint32_t t : editor_.star(a)) {
            const Triangle& tri = editor_.triangle(t);
            if (std::find(tri.begin(), tri.end(), b) != tri.end())
                return reference_.onto_patch(middle, unordered(editor_.side(t)), reach);
        }
        return middle;
    }

    /// The target length of edge ab: the smallest target of the patches around it, and of the layer
    /// sizing at its midpoint.
    double target(std::uint32_t a, std::uint32_t b) const
    {
        double length = options_.target_edge_mm > 0 ? options_.target_edge_mm : std::numeric_limits<double>::max();
        if (options_.edge_per_thickness > 0)
            length = std::min(length, reference_.size_at(0.5 * (editor_.position(a) + editor_.position(b))));
        if (options_.target_edge_mm_by_pair.empty()) return length;
        for (const std::uint32_t t : editor_.star(a)) {
            const Triangle& tri = editor_.triangle(t);
            if (std::find(tri.begin(), tri.end(), b) == tri.end()) continue;
            const auto it = options_.target_edge_mm_by_pair.find(unordered(editor_.side(t)));
            if (it != options_.target_edge_mm_by_pair.end()) length = std::min(length, it->second);
            const auto reversed = options_.target_edge_mm_by_pair.find(
                {unordered(editor_.side(t)).second, unordered(editor_.side(t)).first});
            if (reversed != options_.target_edge_mm_by_pair.end()) length = std::min(length, reversed->second);
        }
        return length;
    }

    /// Every edge (a, b), a < b, sorted: each vertex's from its star, in vertex order (a sort of a few
    /// neighbours each instead of one of all the edges).
    std::vector<Edge> edges() const
    {
        std::vector<Edge> result;
        result.reserve(3 * editor_.triangle_count() / 2 + 16);
        for (std::uint32_t a = 0; a < editor_.vertex_slots(); ++a) {
            const std::size_t first = result.size();
            for (const std::uint32_t t : editor_.star(a))
                for (const std::uint32_t b : editor_.triangle(t))
                    if (b > a) result.emplace_back(a, b);
            std::sort(result.begin() + static_cast<std::ptrdiff_t>(first), result.end());
            result.erase(std::unique(result.begin() + static_cast<std::ptrdiff_t>(first), result.end()), result.end());
        }
        return result;
    }

    double length(const Edge& e) const { return distance(editor_.position(e.first), editor_.position(e.second)); }

    /// Whether collapsing v into w keeps every edge at w within `longest` times its target.
    bool keeps_edges_short(std::uint32_t v, std::uint32_t w, double longest) const
    {
        editor_.ring(v, ring_);
        for (const LocalEditor::RingEntry& e : ring_)
            if (e.vertex != w &&
                distance(editor_.position(e.vertex), editor_.position(w)) > longest * target(v, e.vertex))
                return false;
        return true;
    }

    /// Whether v may collapse into w: no corner, a junction vertex only along its curve, and every edge at w within
    /// `longest` times its target.
    bool may_collapse(std::uint32_t v, std::uint32_t w, double longest) const
    {
        const VertexKind kind = editor_.kind(v);
        if (kind == VertexKind::corner) return false;
        if (kind == VertexKind::curve && editor_.edge_multiplicity(v, w) < 3) return false;
        return keeps_edges_short(v, w, longest);
    }

    void collapse_short_edges()
    {
        std::vector<std::pair<double, Edge>> short_edges;
        for (const Edge& e : edges())
            if (const double l = length(e); l < 0.8 * target(e.first, e.second)) short_edges.push_back({l, e});
        std::sort(short_edges.begin(), short_edges.end());
        for (const auto& [l, e] : short_edges) {
            const auto [a, b] = e;
            if (!editor_.vertex_alive(a) || !editor_.vertex_alive(b) || editor_.edge_multiplicity(a, b) == 0) continue;
            if (length(e) >= 0.8 * target(a, b)) continue;
            if (collapse_into(a, b, 4.0 / 3.0) || collapse_into(b, a, 4.0 / 3.0)) ++report_.collapses;
            else ++report_.refused;
        }
    }

    /// Triangles with an angle below the limit that Botsch and Kobbelt's loop leaves behind, mostly along
    /// junction curves (where edges may not flip and vertices slide along the curve only): a cap (an angle
    /// over 120 degrees) flips its longest edge, or else its apex collapses into an end of that edge; a
    /// needle collapses its shortest edge. Either way as far as the junction rules, the editor's checks and
    /// 1.6 times the target length allow.
    void remove_bad_triangles()
    {
        constexpr double bad_deg = 25;
        std::vector<std::pair<double, std::uint32_t>> bad;
        for (std::uint32_t t = 0; t < editor_.triangle_slots(); ++t)
            if (editor_.triangle_alive(t))
                if (const double a = detail::smallest_angle_deg(editor_.corners(t)); a < bad_deg)
                    bad.emplace_back(a, t);
        std::sort(bad.begin(), bad.end());
        const auto collapse = [&](std::uint32_t v, std::uint32_t w) { return collapse_into(v, w, 1.6); };
        const auto collapse_either = [&](std::uint32_t a, std::uint32_t b) { return collapse(a, b) || collapse(b, a); };
        for (const auto& [angle, t] : bad) {
            if (!editor_.triangle_alive(t)) continue;
            const Triangle tri = editor_.triangle(t);
            const TriangleCorners c = editor_.corners(t);
            int apex = 0, shortest = 0; // the corner of the largest angle; the shortest edge (from corner k)
            double largest = 0, lengths[3];
            for (int k = 0; k < 3; ++k) {
                const Vec3 u = c[(k + 1) % 3] - c[k], w = c[(k + 2) % 3] - c[k];
                const double at = std::atan2(norm(cross(u, w)), dot(u, w));
                if (at > largest) largest = at, apex = k;
                lengths[k] = norm(u);
            }
            for (int k = 1; k < 3; ++k)
                if (lengths[k] < lengths[shortest]) shortest = k;
            bool fixed = false;
            if (largest > 2.0944) { // 120 degrees: a cap
                const std::uint32_t x = tri[(apex + 1) % 3], y = tri[(apex + 2) % 3];
                fixed = (editor_.edge_multiplicity(x, y) == 2 && editor_.try_flip(x, y)) || collapse(tri[apex], x) ||
                        collapse(tri[apex], y);
                if (fixed && editor_.vertex_alive(tri[apex])) ++report_.flips;
                else if (fixed) ++report_.collapses;
            } else if (lengths[shortest] < 0.5 * std::max({lengths[0], lengths[1], lengths[2]})) {
                fixed = collapse_either(tri[shortest], tri[(shortest + 1) % 3]);
                if (fixed) ++report_.collapses;
            }
            if (!fixed) ++report_.refused;
        }
    }

    int valence_target(std::uint32_t v) const { return editor_.kind(v) == VertexKind::patch ? 6 : 4; }

    int deviation(const std::vector<int>& valence, std::uint32_t v, int change) const
    {
        return std::abs(valence[v] + change - valence_target(v));
    }

    void flip_towards_valence_six()
    {
        // Valences (distinct neighbours) kept up to date through the flips: a flip of vw towards ab takes one
        // from v and w and gives one to a and b (vw had only those two triangles; ab was no edge).
        std::vector<int> valence(editor_.vertex_slots(), 0);
        for (std::uint32_t v = 0; v < editor_.vertex_slots(); ++v)
            if (editor_.vertex_alive(v)) editor_.ring(v, ring_), valence[v] = static_cast<int>(ring_.size());
        for (const Edge& e : edges()) {
            const auto [v, w] = e;
            if (editor_.edge_multiplicity(v, w) != 2) continue;
            const std::optional<std::array<std::uint32_t, 2>> opposite = editor_.opposite_vertices(v, w);
            if (!opposite) continue;
            const std::array<std::uint32_t, 2>& apexes = *opposite;
            const int before = deviation(valence, v, 0) + deviation(valence, w, 0) + deviation(valence, apexes[0], 0) +
                               deviation(valence, apexes[1], 0);
            const int after = deviation(valence, v, -1) + deviation(valence, w, -1) + deviation(valence, apexes[0], 1) +
                              deviation(valence, apexes[1], 1);
            if (after >= before) continue;
            if (editor_.try_flip(v, w)) {
                ++report_.flips;
                --valence[v], --valence[w], ++valence[apexes[0]], ++valence[apexes[1]];
            } else {
                ++report_.refused;
            }
        }
    }

    /// Flips edges of one patch whose two opposite angles add up to more than a half turn, where the two
    /// triangles lie nearly in one plane: each such flip raises the smaller of the pair's smallest angles
    /// (the Delaunay criterion), and surfaces with larger smallest angles give TetGen better tetrahedra.
    void flip_towards_delaunay()
    {
        constexpr double max_fold_cos = 0.9659; // the two triangles' normals within 15 degrees
        for (const Edge& e : edges()) {
            const auto [v, w] = e;
            if (editor_.edge_multiplicity(v, w) != 2) continue;
            std::array<std::uint32_t, 2> apex{}, pair{};
            int n = 0;
            for (const std::uint32_t t : editor_.star(v)) {
                const Triangle& tri = editor_.triangle(t);
                if (std::find(tri.begin(), tri.end(), w) == tri.end() || n == 2) continue;
                pair[n] = t;
                for (const std::uint32_t u : tri)
                    if (u != v && u != w) apex[n] = u;
                ++n;
            }
            if (n != 2 || !(editor_.side(pair[0]) == editor_.side(pair[1]))) continue;
            const Vec3 &pv = editor_.position(v), &pw = editor_.position(w);
            const auto angle_at = [&](std::uint32_t a) {
                const Vec3 x = pv - editor_.position(a), y = pw - editor_.position(a);
                return std::atan2(norm(cross(x, y)), dot(x, y));
            };
            if (angle_at(apex[0]) + angle_at(apex[1]) <= 3.14159265358979323846 + 1e-9) continue;
            const TriangleCorners c0 = editor_.corners(pair[0]), c1 = editor_.corners(pair[1]);
            const Vec3 n0 = cross(c0[1] - c0[0], c0[2] - c0[0]), n1 = cross(c1[1] - c1[0], c1[2] - c1[0]);
            if (dot(n0, n1) < max_fold_cos * norm(n0) * norm(n1)) continue;
            if (editor_.try_flip(v, w)) ++report_.flips;
            else ++report_.refused;
        }
    }

    /// Whether moving patch vertex v to p, or collapsing it into w (at p, w's position), would carry the centre of a
    /// voxel next to another label across the surface (counted as refused). Junction vertices are not asked: their
    /// stars hold several patches.
    bool carries_a_centre(std::uint32_t v, const Vec3& p, std::optional<std::uint32_t> w = std::nullopt)
    {
        if (sides_ == nullptr || editor_.kind(v) != VertexKind::patch) return false;
        before_.clear(), after_.clear();
        for (const std::uint32_t t : editor_.star(v)) {
            const Triangle& tri = editor_.triangle(t);
            TriangleCorners c = editor_.corners(t);
            before_.push_back(c);
            if (w && std::find(tri.begin(), tri.end(), *w) != tri.end()) continue; // dies with the collapse
            for (int k = 0; k < 3; ++k)
                if (tri[k] == v) c[k] = p;
            after_.push_back(c);
        }
        if (!sides_->carries_a_centre(before_, after_)) return false;
        ++report_.refused_by_voxels;
        return true;
    }

    /// Collapses v into w when may_collapse(v, w, longest), the voxels' sides and the editor allow it. The voxels
    /// are asked after the editor's cheap checks (topology, shape, tilt), which refuse most collapses tried, and
    /// before its costly ones: the same collapses as asking them first, for fewer voxel tests.
    bool collapse_into(std::uint32_t v, std::uint32_t w, double longest)
    {
        return may_collapse(v, w, longest) &&
               editor_.try_collapse(v, w, [&] { return !carries_a_centre(v, editor_.position(w), w); });
    }

    /// Area-weighted normal of v's star.
    Vec3 normal_at(std::uint32_t v) const
    {
        Vec3 n{0, 0, 0};
        for (const std::uint32_t t : editor_.star(v)) {
            const TriangleCorners c = editor_.corners(t);
            n = n + cross(c[1] - c[0], c[2] - c[0]);
        }
        const double length = norm(n);
        return length > 0 ? (1.0 / length) * n : n;
    }

    void relax()
    {
        for (std::uint32_t v = 0; v < editor_.vertex_slots(); ++v) {
            if (!editor_.vertex_alive(v) || editor_.kind(v) == VertexKind::corner) continue;
            const bool curve = editor_.kind(v) == VertexKind::curve;
            const std::vector<std::uint32_t> ring = curve ? editor_.curve_neighbours(v) : editor_.neighbours(v);
            Vec3 mean{0, 0, 0};
            for (const std::uint32_t u : ring) mean = mean + editor_.position(u);
            mean = (1.0 / static_cast<double>(ring.size())) * mean;
            const Vec3& p = editor_.position(v);
            Vec3 target_point = mean;
            const double edge = target(v, ring.front());
            const double reach = 2 * edge + distance(p, mean);
            if (curve) {
                target_point = reference_.onto_curve(mean, reach);
            } else {
                const Vec3 n = normal_at(v);
                const Vec3 tangential = p + (mean - p) - dot(mean - p, n) * n;
                target_point =
                    reference_.onto_patch(tangential, unordered(editor_.side(editor_.star(v).front())), reach);
            }
            // So short a move is not worth judging (RemeshOptions::min_relax_move; its figures: docs/surfaces.md).
            if (distance(p, target_point) < options_.min_relax_move * edge) continue;
            if (carries_a_centre(v, target_point)) continue;
            if (editor_.try_move(v, target_point)) ++report_.moves;
            else ++report_.refused;
        }
    }

    const RemeshOptions& options_;
    RemeshReport& report_;
    LocalEditor editor_;
    const Reference& reference_;
    const detail::VoxelSides* sides_;
    mutable std::vector<LocalEditor::RingEntry> ring_; ///< scratch
    std::vector<TriangleCorners> before_, after_;      ///< scratch of carries_a_centre()
};

/// Largest distance from a vertex of `result` to the input (patch vertices to their patch, others to any
/// input triangle), for the report.
double distance_to_input(const InterfaceComplex& result, const Reference& reference, double cell_mm)
{
    double largest = 0;
    std::vector<char> seen(result.vertex_count(), 0);
    for (std::size_t t = 0; t < result.triangle_count(); ++t)
        for (const std::uint32_t v : result.triangles[t]) {
            if (seen[v]) continue;
            seen[v] = 1;
            const Vec3& p = result.vertices[v];
            const Vec3 q = reference.onto_patch(p, unordered(result.sides[t]), 4 * cell_mm);
            largest = std::max(largest, distance(p, q));
        }
    return largest;
}

/// How many slabs to remesh side by side: options.slabs, or one per 125 000 triangles (at most 8). Not two from
/// fewer triangles on, as decimation cuts: the bands around the cuts are remeshed twice and, narrow (2.5 target
/// edges either side), keep more thin triangles. The 1 mm sphere head's coarse decimated surface (63 316 triangles,
/// 2 mm target) in two slabs: 1 408 triangles under 20 degrees, 1 075 of them within 12 mm of the cut, against 427
/// and 86 in one slab (bands of 6 edges: 402 and 69); the subtraction dipoles on the z axis, which lies in the band,
/// lost accuracy (RDM 0.013 -> 0.044 at eccentricity 0.9).
std::size_t slab_count(const InterfaceComplex& complex, const RemeshOptions& options)
{
    if (options.slabs > 0) return options.slabs;
    return std::clamp<std::size_t>(complex.triangle_count() / 125'000, 1, 8);
}

/// Remeshes the slabs marked in `run` side by side (in parallel), each behind its fence (the slab shrunk by
/// more than the gap: slabs.h), and puts the whole together. Independent of the thread count.
InterfaceComplex remesh_slabs(const InterfaceComplex& complex, const std::vector<Slab>& slabs,
                              const std::vector<char>& run, const Reference& reference, const RemeshOptions& options,
                              double cell_mm, const detail::VoxelSides* sides, RemeshReport& report)
{
    std::vector<detail::EditedSlab> edited(slabs.size());
    for (std::size_t k = 0; k < slabs.size(); ++k) edited[k].slab = slabs[k];
    std::vector<RemeshReport> reports(slabs.size());
    detail::edit_slabs(complex, slabs, run, [&](std::size_t k, detail::SlabPiece& piece) {
        Remesher remesher(std::move(piece.complex), reference, options, cell_mm, reports[k], sides,
                          slabs[k].fence(options.min_gap_mm));
        remesher.run({});
        edited[k].edited = remesher.editor().snapshot();
        edited[k].from_vertex = std::move(piece.from_vertex);
    });
    for (const RemeshReport& part : reports) {
        report.splits += part.splits;
        report.collapses += part.collapses;
        report.flips += part.flips;
        report.moves += part.moves;
        report.refused += part.refused;
        report.refused_by_voxels += part.refused_by_voxels;
    }
    return detail::merge_slabs(complex, edited);
}

/// Bands around the cuts between `slabs`, to remesh what their fences held back: half-width `reach` (at most
/// 0.45 of either neighbour's width), with the rest between them left as it is (run 0).
std::vector<std::pair<Slab, char>> seam_bands(const std::vector<Slab>& slabs, double reach)
{
    const auto width = [](const Slab& slab) {
        return std::isfinite(slab.high - slab.low) ? slab.high - slab.low : std::numeric_limits<double>::max();
    };
    std::vector<std::pair<Slab, char>> bands;
    const int axis = slabs.front().axis;
    double from = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k + 1 < slabs.size(); ++k) {
        const double cut = slabs[k].high, half = std::min({reach, 0.45 * width(slabs[k]), 0.45 * width(slabs[k + 1])});
        bands.push_back({{axis, from, cut - half}, 0});
        bands.push_back({{axis, cut - half, cut + half}, 1});
        from = cut + half;
    }
    bands.push_back({{axis, from, std::numeric_limits<double>::infinity()}, 0});
    return bands;
}

/// The largest target edge length of any patch.
double largest_target(const RemeshOptions& options)
{
    double target = options.target_edge_mm;
    for (const auto& [pair, length] : options.target_edge_mm_by_pair) target = std::max(target, length);
    return target;
}

/// Slabs to remesh side by side: `count` (see slab_count()), fewer while one would be narrower than six
/// target edges (its fence would hold back much of it). Widths are measured within the complex's extent.
std::vector<Slab> cut_for_remeshing(const InterfaceComplex& complex, std::size_t count, const RemeshOptions& options)
{
    for (;; --count) {
        std::vector<Slab> slabs = detail::cut_into_slabs(complex, count);
        const int axis = slabs.front().axis;
        double low = std::numeric_limits<double>::max(), high = -low;
        for (const Vec3& p : complex.vertices) low = std::min(low, p[axis]), high = std::max(high, p[axis]);
        double narrowest = std::numeric_limits<double>::max();
        for (const Slab& slab : slabs)
            narrowest = std::min(narrowest, std::min(slab.high, high) - std::max(slab.low, low));
        if (slabs.size() <= 1 || narrowest >= 6 * largest_target(options)) return slabs;
    }
}

} // namespace

RemeshReport remesh(InterfaceComplex& complex, const RemeshOptions& options, const Progress& progress)
{
    validate(options);
    validate_indices(complex, "remesh input");
    RemeshReport report;
    report.triangles_before = complex.triangle_count();
    report.min_angle_before_deg = smallest_angle_deg(complex);
    report.min_sector_before_deg = detail::smallest_sector_deg(complex);
    const InterfaceComplex input = complex;
    const double cell_mm = 2 * std::max(detail::mean_edge_length(complex), options.target_edge_mm);
    const Reference reference(
        input, cell_mm,
        {.target_edge_mm = largest_target(options),
         .edges_per_mm = options.edge_per_thickness,
         .min_edge_mm = options.min_edge_mm > 0 ? options.min_edge_mm : largest_target(options) / 3});
    report.thin_triangles = reference.sizing().thin_triangles();
    std::optional<detail::VoxelSides> sides;
    if (options.voxel_image != nullptr) sides.emplace(*options.voxel_image);
    const detail::VoxelSides* sides_of_voxels = sides ? &*sides : nullptr;
    const auto began = std::chrono::steady_clock::now();
    const auto seconds = [&] {
        return format_mm(std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count(), 1);
    };
    const std::size_t count = slab_count(complex, options);
    if (count > 1) {
        // Long edges are split first, over the whole: no triangle is then so long that the fences of the
        // slabs hold it back everywhere.
        Remesher splitter(std::move(complex), reference, options, cell_mm, report, sides_of_voxels);
        splitter.split_long_edges();
        complex = splitter.editor().result();
        progress.debug("remesh", concat("long edges split over the whole: ", complex.triangle_count(), " triangles (",
                                        seconds(), " s)"));
    }
    const std::vector<Slab> slabs = count > 1 ? cut_for_remeshing(complex, count, options) : std::vector<Slab>{};
    if (slabs.size() > 1) {
        // Slabs side by side, then bands around the cuts between them (slabs.h).
        report.slabs = slabs.size();
        complex = remesh_slabs(complex, slabs, std::vector<char>(slabs.size(), 1), reference, options, cell_mm,
                               sides_of_voxels, report);
        progress.debug("remesh", concat(slabs.size(), " slabs remeshed: ", complex.triangle_count(), " triangles (",
                                        seconds(), " s)"));
        progress.update("remesh", 0.8);
        std::vector<Slab> bands;
        std::vector<char> run;
        // What the fences held back lies within about one edge (at most 4/3 of the target after the split)
        // of each cut: bands of 2.5 target edges either side hold it, and their own fences lie where the
        // slabs were remeshed.
        for (const auto& [band, edit] : seam_bands(slabs, 2.5 * largest_target(options) + options.min_gap_mm))
            bands.push_back(band), run.push_back(edit);
        // One round in the bands, where the slabs had three: what the fences held back was split with the rest
        // but never collapsed, flipped or relaxed, which one round does, and the rest of each band was remeshed in
        // its slab (1 mm usc19-5 head: remeshing 13.7-13.9 -> 12.1-13.1 s, 1% more triangles, every tissue's Dice
        // after tm-tetra as high or higher; docs/surfaces.md).
        RemeshOptions band_options = options;
        band_options.iterations = std::min<std::size_t>(options.iterations, 1);
        complex = remesh_slabs(complex, bands, run, reference, band_options, cell_mm, sides_of_voxels, report);
        progress.debug("remesh", concat("the bands around the cuts remeshed: ", complex.triangle_count(),
                                        " triangles (", seconds(), " s)"));
    } else {
        Remesher remesher(std::move(complex), reference, options, cell_mm, report, sides_of_voxels);
        remesher.run(progress);
        complex = remesher.editor().result();
    }
    report.triangles_after = complex.triangle_count();
    report.min_angle_after_deg = smallest_angle_deg(complex);
    report.min_sector_after_deg = detail::smallest_sector_deg(complex);
    report.mean_edge_after_mm = detail::mean_edge_length(complex);
    report.max_distance_mm = distance_to_input(complex, reference, cell_mm);
    progress.info("remesh",
                  concat(report.triangles_before, " -> ", report.triangles_after, " triangles; smallest angle ",
                         format_mm(report.min_angle_before_deg, 2), " -> ", format_mm(report.min_angle_after_deg, 2),
                         " deg; smallest tissue sector ", format_mm(report.min_sector_before_deg, 2), " -> ",
                         format_mm(report.min_sector_after_deg, 2), " deg"));
    return report;
}

} // namespace tissuemesh::surface

#include "surface/check_complex.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <set>

#include "core/error.h"
#include "surface/detail/cgal_intersections.h"
#include "surface/detail/mesh_measures.h"
#include "surface/detail/check_topology.h"
#include "surface/detail/defect_log.h"
#include "surface/detail/edge_fan.h"

namespace tissuemesh::surface {
namespace {

using detail::DefectLog;
constexpr std::uint32_t no_triangle = std::numeric_limits<std::uint32_t>::max();

/// Whether two of the items 0..n-1 are equal (`same`), found by hashing (`hash`): the common answer "none"
/// costs a pass instead of the sort that lists the repeats.
template <class Hash, class Same>
bool has_repeats(std::size_t n, Hash hash, Same same)
{
    std::size_t size = 16;
    while (size < 2 * n) size *= 2;
    std::vector<std::uint32_t> table(size, no_triangle); // item indices; no_triangle: empty
    for (std::uint32_t i = 0; i < n; ++i)
        for (std::size_t slot = hash(i) & (size - 1);; slot = (slot + 1) & (size - 1)) {
            if (table[slot] == no_triangle) {
                table[slot] = i;
                break;
            }
            if (same(table[slot], i)) return true;
        }
    return false;
}

std::uint64_t mix(std::uint64_t h, std::uint64_t x)
{
    h = (h ^ x) * 0x9e3779b97f4a7c15ull;
    return h ^ (h >> 29);
}

/// Maps every vertex to the lowest index at the same coordinates, and logs every further vertex used
/// by a triangle there: triangles must share vertex indices, or the tissues' surfaces are open.
std::vector<std::uint32_t> merge_coincident_vertices(DefectLog& log, CheckReport& report)
{
    const InterfaceComplex& complex = log.complex();
    std::vector<std::uint32_t> first_user(complex.vertices.size(), no_triangle);
    for (std::uint32_t t = 0; t < complex.triangles.size(); ++t)
        for (const std::uint32_t v : complex.triangles[t])
            if (first_user[v] == no_triangle) first_user[v] = t;
    std::vector<std::uint32_t> used;
    for (std::uint32_t v = 0; v < first_user.size(); ++v)
        if (first_user[v] != no_triangle) used.push_back(v);
    report.vertices = used.size();
    std::vector<std::uint32_t> canonical(complex.vertices.size());
    std::iota(canonical.begin(), canonical.end(), 0u);
    // Coordinates hashed as bit patterns, -0 as 0 (which == treats as equal).
    const auto position_hash = [&](std::uint32_t i) {
        std::uint64_t h = 0;
        for (const double c : complex.vertices[used[i]]) h = mix(h, std::bit_cast<std::uint64_t>(c + 0.0));
        return static_cast<std::size_t>(h);
    };
    const auto same_position = [&](std::uint32_t a, std::uint32_t b) {
        return complex.vertices[used[a]] == complex.vertices[used[b]];
    };
    if (!has_repeats(used.size(), position_hash, same_position)) return canonical;
    std::sort(used.begin(), used.end(), [&](std::uint32_t a, std::uint32_t b) {
        return complex.vertices[a] != complex.vertices[b] ? complex.vertices[a] < complex.vertices[b] : a < b;
    });
    for (std::size_t i = 1; i < used.size(); ++i) {
        const std::uint32_t keep = canonical[used[i - 1]], v = used[i];
        if (complex.vertices[v] != complex.vertices[keep]) continue;
        canonical[v] = keep;
        log.add(DefectKind::duplicate_vertex, [&] {
            Defect defect;
            defect.location_mm = complex.vertices[v];
            defect.triangles = {first_user[keep], first_user[v]};
            for (const std::uint32_t t : defect.triangles)
                defect.tissues.insert(defect.tissues.end(), {complex.sides[t].from, complex.sides[t].to});
            defect.description = concat("duplicate vertices ", keep, " and ", v, " at the same position (used by ",
                                        log.triangle(first_user[keep]), " and ", log.triangle(first_user[v]), ") ",
                                        DefectLog::near(defect.location_mm), "; triangles must share vertex indices");
            return defect;
        });
    }
    return canonical;
}

Defect triangle_defect(const DefectLog& log, std::uint32_t t, const std::string& what)
{
    Defect defect;
    defect.location_mm = log.centroid(t);
    defect.triangles = {t};
    defect.tissues = {log.complex().sides[t].from, log.complex().sides[t].to};
    defect.description = concat(what, ' ', log.triangle(t), ' ', DefectLog::near(defect.location_mm));
    return defect;
}

/// Logs degenerate triangles (a repeated vertex once coincident vertices are merged, or exactly
/// collinear vertices) and warns about needles; returns which triangles are degenerate.
std::vector<char> check_shapes(DefectLog& log, const std::vector<Triangle>& merged, double needle_angle_deg)
{
    const InterfaceComplex& complex = log.complex();
    std::vector<char> degenerate(merged.size(), 0);
    const detail::AngleLimit needle(needle_angle_deg);
    for (std::uint32_t t = 0; t < merged.size(); ++t) {
        const Triangle& tri = merged[t];
        const std::array<Vec3, 3> p{complex.vertices[tri[0]], complex.vertices[tri[1]], complex.vertices[tri[2]]};
        const bool repeated = tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0];
        if (repeated || detail::are_collinear(p[0], p[1], p[2])) {
            degenerate[t] = 1;
            log.add(DefectKind::degenerate_triangle, [&] {
                return triangle_defect(log, t,
                                       repeated ? "degenerate (repeated vertex)" : "degenerate (collinear vertices)");
            });
            continue;
        }
        // The exact angle only where it is below the limit (has_angle_below decides most without atan2).
        if (!detail::has_angle_below(p, needle)) continue;
        const double angle = detail::smallest_angle_deg(p);
        log.add(DefectKind::needle_triangle, [&] {
            return triangle_defect(log, t, concat("needle (smallest angle ", format_mm(angle, 4), " deg)"));
        });
    }
    return degenerate;
}

/// Logs every non-degenerate triangle on the same vertex set as an earlier one, and marks it in `skip`.
void check_duplicates(DefectLog& log, const std::vector<Triangle>& merged, std::vector<char>& skip)
{
    // The common answer "none" by hashing (a pass), the sort below only when some triangle repeats.
    std::vector<std::uint32_t> kept;
    for (std::uint32_t t = 0; t < merged.size(); ++t)
        if (!skip[t]) kept.push_back(t);
    const auto vertex_set = [&](std::uint32_t i) {
        Triangle k = merged[kept[i]];
        std::sort(k.begin(), k.end());
        return k;
    };
    const auto set_hash = [&](std::uint32_t i) {
        std::uint64_t h = 0;
        for (const std::uint32_t v : vertex_set(i)) h = mix(h, v);
        return static_cast<std::size_t>(h);
    };
    if (!has_repeats(kept.size(), set_hash,
                     [&](std::uint32_t a, std::uint32_t b) { return vertex_set(a) == vertex_set(b); }))
        return;
    std::vector<std::pair<Triangle, std::uint32_t>> sorted;
    for (std::uint32_t t = 0; t < merged.size(); ++t) {
        if (skip[t]) continue;
        Triangle key = merged[t];
        std::sort(key.begin(), key.end());
        sorted.emplace_back(key, t);
    }
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 1, first = 0; i < sorted.size(); ++i) {
        if (sorted[i].first != sorted[first].first) {
            first = i;
            continue;
        }
        const std::uint32_t original = sorted[first].second, t = sorted[i].second;
        skip[t] = 1;
        log.add(DefectKind::duplicate_triangle, [&] {
            Defect defect = triangle_defect(log, t, "");
            defect.triangles.insert(defect.triangles.begin(), original);
            defect.tissues.insert(defect.tissues.end(),
                                  {log.complex().sides[original].from, log.complex().sides[original].to});
            defect.description = concat("duplicate triangles: ", log.triangle(original), " and ", log.triangle(t),
                                        " have the same vertices ", DefectLog::near(defect.location_mm));
            return defect;
        });
    }
}

bool same_patch(const LabelPair& a, const LabelPair& b)
{
    return (a.from == b.from && a.to == b.to) || (a.from == b.to && a.to == b.from);
}

std::array<Vec3, 3> corners(const InterfaceComplex& complex, std::uint32_t t)
{
    const Triangle& tri = complex.triangles[t];
    return {complex.vertices[tri[0]], complex.vertices[tri[1]], complex.vertices[tri[2]]};
}

/// Logs intersecting pairs; returns the tissues involved in any.
std::set<Label> check_intersections(DefectLog& log, const std::vector<Triangle>& merged, const std::vector<char>& skip)
{
    std::set<Label> crossing;
    const InterfaceComplex& complex = log.complex();
    std::vector<std::uint32_t> candidates;
    for (std::uint32_t t = 0; t < merged.size(); ++t)
        if (!skip[t]) candidates.push_back(t);
    for (const auto& [a, b] : detail::find_intersecting_pairs(complex.vertices, merged, candidates)) {
        const bool self = same_patch(complex.sides[a], complex.sides[b]);
        crossing.insert({complex.sides[a].from, complex.sides[a].to, complex.sides[b].from, complex.sides[b].to});
        log.add(self ? DefectKind::self_intersection : DefectKind::patch_intersection, [&, a = a, b = b] {
            Defect defect;
            defect.location_mm = detail::intersection_point(corners(complex, a), corners(complex, b));
            defect.triangles = {a, b};
            defect.tissues = {complex.sides[a].from, complex.sides[a].to, complex.sides[b].from, complex.sides[b].to};
            defect.description =
                concat(self ? "self-intersection between " : "intersection between patches: ", log.triangle(a), " and ",
                       log.triangle(b), ' ', DefectLog::near(defect.location_mm));
            return defect;
        });
    }
    return crossing;
}

void validate_options(const CheckOptions& options, std::size_t triangles)
{
    if (!(options.needle_angle_deg >= 0 && options.needle_angle_deg <= 60))
        throw InputError(concat("check options: needle angle ", options.needle_angle_deg,
                                " deg is outside [0, 60]; no triangle has a smallest angle above 60 deg"));
    if (triangles >= no_triangle)
        throw InputError(concat("interface complex: ", triangles, " triangles exceed the checker's limit of ",
                                no_triangle - 1, "; split the complex"));
}

} // namespace

std::string_view to_string(DefectKind kind)
{
    static constexpr std::array<std::string_view, defect_kind_count> names{
        "open-edge",         "orientation-conflict", "non-manifold-edge",  "inverted-tissue",
        "tangled-junction",  "degenerate-triangle",  "duplicate-triangle", "duplicate-vertex",
        "self-intersection", "patch-intersection",   "needle-triangle"};
    return names[static_cast<std::size_t>(kind)];
}

bool is_error(DefectKind kind) { return kind != DefectKind::needle_triangle; }

std::size_t CheckReport::error_count() const
{
    std::size_t total = 0;
    for (std::size_t k = 0; k < defect_kind_count; ++k) total += is_error(static_cast<DefectKind>(k)) ? counts[k] : 0;
    return total;
}

std::size_t CheckReport::warning_count() const
{
    return std::accumulate(counts.begin(), counts.end(), std::size_t{0}) - error_count();
}

const Defect* CheckReport::first_error() const
{
    for (const Defect& defect : defects)
        if (is_error(defect.kind)) return &defect;
    return nullptr;
}

CheckReport check_complex(const InterfaceComplex& complex, const CheckOptions& options, const Progress& progress)
{
    validate_indices(complex, "interface complex");
    validate_options(options, complex.triangles.size());
    CheckReport report;
    report.triangles = complex.triangles.size();
    DefectLog log(complex, options.max_defects_per_kind, report);
    progress.update("check", 0);

    const std::vector<std::uint32_t> canonical = merge_coincident_vertices(log, report);
    std::vector<Triangle> merged(complex.triangles.size());
    for (std::size_t t = 0; t < merged.size(); ++t)
        for (int k = 0; k < 3; ++k) merged[t][k] = canonical[complex.triangles[t][k]];
    std::vector<char> skip = check_shapes(log, merged, options.needle_angle_deg);
    check_duplicates(log, merged, skip);
    progress.update("check", 0.1);

    detail::check_tissue_surfaces(log, report);
    detail::check_edges(log, merged, skip, report);
    progress.update("check", 0.3);

    std::set<Label> crossing;
    if (options.check_intersections) {
        crossing = check_intersections(log, merged, skip);
        report.intersections_checked = true;
    }
    detail::check_volume_signs(log, report, crossing);
    progress.update("check", 1);
    std::stable_sort(report.defects.begin(), report.defects.end(),
                     [](const Defect& a, const Defect& b) { return a.kind < b.kind; });
    progress.debug("check", concat(report.triangles, " triangles, ", report.tissues.size(), " tissues, ",
                                   report.error_count(), " errors, ", report.warning_count(), " warnings"));
    return report;
}

void require_fit_for_tetrahedralization(const InterfaceComplex& complex, const std::string& what)
{
    if (complex.triangles.empty())
        throw InputError(concat(what, ": the interface complex has no triangle, so no tissue is enclosed; "
                                      "extract the interfaces first (tm-extract)"));
    const CheckReport report = check_complex(complex, {.max_defects_per_kind = 1});
    if (report.ok()) return;
    const Defect* first = report.first_error();
    throw InputError(concat(what, ": not fit for tetrahedralization: ", report.error_count(), " defect",
                            report.error_count() == 1 ? "" : "s", ", first: ", first ? first->description : "?",
                            "; tm-check-surface lists them; ", repair_hint(report)));
}

std::string repair_hint(const CheckReport& report)
{
    const std::string extract = "re-extract it with tm-extract, whose output is always fit, and edit it only with "
                                "tm-smooth, tm-decimate and tm-remesh, which keep it fit";
    // Doubled vertices and triangles open edges that merging them closes again: then the open edges say nothing.
    const bool doubles = report.count(DefectKind::duplicate_vertex) + report.count(DefectKind::duplicate_triangle) > 0;
    for (const DefectKind kind : {DefectKind::open_edge, DefectKind::non_manifold_edge, DefectKind::inverted_tissue,
                                  DefectKind::tangled_junction})
        if (report.count(kind) > 0 && !doubles)
            return concat("tm-repair cannot fix ", to_string(kind), " defects (it changes no topology): ", extract);
    return concat("tm-repair may fix it (it merges coincident vertices, drops repeated and zero-area triangles, turns "
                  "flipped ones and moves crossing surfaces apart), or ",
                  extract);
}

double smallest_tissue_sector_deg(const InterfaceComplex& complex) { return detail::smallest_sector_deg(complex); }

} // namespace tissuemesh::surface

#include "surface/detail/check_topology.h"

#include <algorithm>
#include <exception>
#include <functional>
#include <numeric>

#include "core/union_find.h"
#include "surface/check_complex.h"
#include "surface/detail/edge_fan.h"

namespace tissuemesh::surface::detail {
namespace {

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b)
{
    return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}
std::uint32_t key_low(std::uint64_t key) { return static_cast<std::uint32_t>(key >> 32); }
std::uint32_t key_high(std::uint64_t key) { return static_cast<std::uint32_t>(key & 0xffffffffu); }

/// One use of an undirected edge by a triangle of a tissue's outward surface.
struct EdgeUse {
    std::uint64_t key;
    std::uint32_t local;    ///< the triangle's index in the tissue's triangle list
    std::int32_t direction; ///< +1 when traversed from the lower to the higher vertex index
};

/// The triangle as seen from `tissue`: normal pointing out of it.
Triangle outward(const InterfaceComplex& complex, std::uint32_t t, Label tissue)
{
    const Triangle& tri = complex.triangles[t];
    return complex.sides[t].from == tissue ? tri : Triangle{tri[0], tri[2], tri[1]};
}

/// Offsets of `vertices` buckets (one more for the end) holding the items counted by count(bucket).
std::vector<std::uint32_t> bucket_starts(std::size_t vertices, const std::vector<std::uint32_t>& sizes)
{
    std::vector<std::uint32_t> start(vertices + 1, 0);
    for (std::size_t v = 0; v < vertices; ++v) start[v + 1] = start[v] + sizes[v];
    return start;
}

/// Sorts each bucket [start[v], start[v + 1]) of `items` by `less` (buckets hold a few items: the edges
/// of one vertex towards higher indices).
template <class T, class Less>
void sort_buckets(std::vector<T>& items, const std::vector<std::uint32_t>& start, Less less)
{
    for (std::size_t v = 0; v + 1 < start.size(); ++v)
        for (std::uint32_t i = start[v] + 1; i < start[v + 1]; ++i)
            for (std::uint32_t j = i; j > start[v] && less(items[j], items[j - 1]); --j)
                std::swap(items[j], items[j - 1]);
}

/// The uses of the edges of a tissue's surface, sorted by edge, then by triangle. Filed by the edge's
/// lower vertex first (a counting sort): far cheaper than sorting tens of millions of uses by comparison.
std::vector<EdgeUse> edge_uses(const InterfaceComplex& complex, Label tissue,
                               const std::vector<std::uint32_t>& triangles)
{
    const auto for_each_use = [&](auto action) {
        for (std::uint32_t local = 0; local < triangles.size(); ++local) {
            const Triangle tri = outward(complex, triangles[local], tissue);
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
                if (a != b) action(EdgeUse{edge_key(a, b), local, a < b ? 1 : -1});
            }
        }
    };
    std::vector<std::uint32_t> sizes(complex.vertices.size(), 0);
    for_each_use([&](const EdgeUse& use) { ++sizes[key_low(use.key)]; });
    const std::vector<std::uint32_t> start = bucket_starts(complex.vertices.size(), sizes);
    std::vector<EdgeUse> uses(start.back());
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for_each_use([&](const EdgeUse& use) { uses[next[key_low(use.key)]++] = use; });
    sort_buckets(uses, start,
                 [](const EdgeUse& x, const EdgeUse& y) { return x.key != y.key ? x.key < y.key : x.local < y.local; });
    return uses;
}

/// Signed volume enclosed by the tissue's outward triangles, relative to `origin` (which cancels for
/// a closed surface but keeps the terms small).
double enclosed_volume(const InterfaceComplex& complex, Label tissue, const std::vector<std::uint32_t>& triangles,
                       const Vec3& origin)
{
    double sum = 0;
    for (const std::uint32_t t : triangles) {
        const Triangle tri = outward(complex, t, tissue);
        const Vec3 a = complex.vertices[tri[0]] - origin;
        const Vec3 b = complex.vertices[tri[1]] - origin;
        const Vec3 c = complex.vertices[tri[2]] - origin;
        sum += dot(a, cross(b, c));
    }
    return sum / 6.0;
}

/// Logs the defects of one edge of a tissue's surface, given its uses [begin, end).
void check_edge(DefectLog& log, Label tissue, const std::vector<std::uint32_t>& triangles, const EdgeUse* begin,
                const EdgeUse* end, TissueCheck& check)
{
    const auto count = static_cast<std::size_t>(end - begin);
    int balance = 0;
    for (const EdgeUse* use = begin; use != end; ++use) balance += use->direction;
    const InterfaceComplex& complex = log.complex();
    const std::uint32_t a = key_low(begin->key), b = key_high(begin->key);
    const auto make = [&](const std::string& what) {
        return [&, what] {
            Defect defect;
            defect.location_mm = 0.5 * (complex.vertices[a] + complex.vertices[b]);
            defect.tissues.push_back(tissue);
            std::string examples;
            for (const EdgeUse* use = begin; use != end && use - begin < 2; ++use) {
                const std::uint32_t t = triangles[use->local];
                defect.triangles.push_back(t);
                const LabelPair& pair = complex.sides[t];
                defect.tissues.push_back(pair.from == tissue ? pair.to : pair.from);
                examples += concat(examples.empty() ? "" : ", ", log.triangle(t));
            }
            defect.description = concat(what, ' ', a, '-', b, " in the surface of ", log.tissue(tissue), " (used by ",
                                        count, " of its triangles: ", examples, count > 2 ? ", ..." : "", ") ",
                                        DefectLog::near(defect.location_mm));
            return defect;
        };
    };
    if (count % 2 == 1) {
        ++check.open_edges;
        log.add(DefectKind::open_edge, make("open edge"));
    } else if (balance != 0) {
        ++check.orientation_conflicts;
        log.add(DefectKind::orientation_conflict, make("orientation conflict (uses not in opposite pairs) at edge"));
    }
    if (count > 2) {
        ++check.non_manifold_edges;
        log.add(DefectKind::non_manifold_edge, make("non-manifold edge (the tissue touches itself)"));
    }
}

std::uint32_t first_triangle_of(const InterfaceComplex& complex, Label tissue)
{
    std::uint32_t t = 0;
    while (t + 1 < complex.sides.size() && complex.sides[t].from != tissue && complex.sides[t].to != tissue) ++t;
    return t;
}

void check_sign(DefectLog& log, Label tissue, const TissueCheck& check)
{
    const bool background = tissue == log.complex().background;
    if (!check.closed || !check.oriented || (background ? check.volume_mm3 < 0 : check.volume_mm3 > 0)) return;
    log.add(DefectKind::inverted_tissue, [&] {
        const std::uint32_t first_triangle = first_triangle_of(log.complex(), tissue);
        Defect defect;
        defect.location_mm = log.centroid(first_triangle);
        defect.tissues = {tissue};
        defect.triangles = {first_triangle};
        const std::string name = log.tissue(tissue);
        defect.description =
            background ? concat("the surface of the background (", name, ") encloses ", format_mm(check.volume_mm3),
                                " mm3 instead of a negative volume: the triangles' from/to labels are swapped ",
                                DefectLog::near(defect.location_mm))
                       : concat("the surface of ", name, " encloses ", format_mm(check.volume_mm3),
                                " mm3 (not positive): its triangles' from/to labels are swapped, or ", name,
                                " is unbounded but is not the background ", DefectLog::near(defect.location_mm));
        return defect;
    });
}

Vec3 bounding_box_centre(const InterfaceComplex& complex)
{
    if (complex.vertices.empty()) return {0, 0, 0};
    Vec3 low = complex.vertices[0], high = complex.vertices[0];
    for (const Vec3& v : complex.vertices)
        for (int axis = 0; axis < 3; ++axis) {
            low[axis] = std::min(low[axis], v[axis]);
            high[axis] = std::max(high[axis], v[axis]);
        }
    return 0.5 * (low + high);
}

} // namespace

void check_tissue_surfaces(DefectLog& log, CheckReport& report)
{
    const InterfaceComplex& complex = log.complex();
    std::map<Label, std::vector<std::uint32_t>> by_tissue;
    for (std::uint32_t t = 0; t < complex.triangles.size(); ++t) {
        by_tissue[complex.sides[t].from].push_back(t);
        by_tissue[complex.sides[t].to].push_back(t);
    }
    const Vec3 origin = bounding_box_centre(complex);
    // The tissues side by side (1 mm usc19-5 head's 2.67 M extracted triangles: 0.53 -> 0.3 s on two cores), each
    // keeping the uses of its edges that break a rule; those are logged afterwards, tissue by tissue as before, so
    // the report does not depend on the threads.
    struct Tissue {
        Label label;
        const std::vector<std::uint32_t>* triangles;
        std::vector<std::vector<EdgeUse>> broken; ///< per edge that breaks a rule (check_edge), its uses
        std::size_t components = 0;
        double volume_mm3 = 0;
    };
    std::vector<Tissue> tissues;
    for (const auto& [tissue, triangles] : by_tissue) tissues.push_back({tissue, &triangles, {}, 0, 0});
    std::exception_ptr failure;
#pragma omp parallel for schedule(dynamic, 1)
    for (std::size_t i = 0; i < tissues.size(); ++i) {
        try {
            Tissue& tissue = tissues[i];
            const std::vector<std::uint32_t>& triangles = *tissue.triangles;
            const std::vector<EdgeUse> uses = edge_uses(complex, tissue.label, triangles);
            UnionFind components(triangles.size());
            for (std::size_t begin = 0, end = 0; begin < uses.size(); begin = end) {
                end = begin;
                int balance = 0;
                while (end < uses.size() && uses[end].key == uses[begin].key) {
                    components.unite(uses[begin].local, uses[end].local);
                    balance += uses[end].direction;
                    ++end;
                }
                const std::size_t count = end - begin;
                if (count % 2 == 1 || balance != 0 || count > 2)
                    tissue.broken.emplace_back(uses.begin() + static_cast<std::ptrdiff_t>(begin),
                                               uses.begin() + static_cast<std::ptrdiff_t>(end));
            }
            tissue.components = components.roots();
            tissue.volume_mm3 = enclosed_volume(complex, tissue.label, triangles, origin);
        } catch (...) {
#pragma omp critical(check_tissue_surfaces_failure)
            if (!failure) failure = std::current_exception();
        }
    }
    if (failure) std::rethrow_exception(failure);
    for (const Tissue& tissue : tissues) {
        TissueCheck& check = report.tissues[tissue.label];
        check.triangles = tissue.triangles->size();
        for (const std::vector<EdgeUse>& uses : tissue.broken)
            check_edge(log, tissue.label, *tissue.triangles, uses.data(), uses.data() + uses.size(), check);
        check.closed = check.open_edges == 0;
        check.oriented = check.orientation_conflicts == 0;
        check.components = tissue.components;
        check.volume_mm3 = tissue.volume_mm3;
    }
}

} // namespace tissuemesh::surface::detail

namespace tissuemesh::surface {

std::vector<std::vector<std::uint32_t>> tissue_shells(const InterfaceComplex& complex, Label tissue)
{
    std::vector<std::uint32_t> triangles;
    for (std::uint32_t t = 0; t < complex.triangles.size(); ++t)
        if (complex.sides[t].from == tissue || complex.sides[t].to == tissue) triangles.push_back(t);
    const std::vector<detail::EdgeUse> uses = detail::edge_uses(complex, tissue, triangles);
    UnionFind components(triangles.size());
    for (std::size_t k = 1; k < uses.size(); ++k)
        if (uses[k].key == uses[k - 1].key) components.unite(uses[k - 1].local, uses[k].local);
    // Shells in the order of their first triangle, each in increasing order.
    std::vector<std::vector<std::uint32_t>> shells;
    std::vector<std::size_t> shell_of(triangles.size(), triangles.size());
    for (std::uint32_t i = 0; i < triangles.size(); ++i) {
        std::size_t& shell = shell_of[components.find(i)];
        if (shell == triangles.size()) shell = shells.size(), shells.emplace_back();
        shells[shell].push_back(triangles[i]);
    }
    return shells;
}

} // namespace tissuemesh::surface

namespace tissuemesh::surface::detail {

void check_volume_signs(DefectLog& log, const CheckReport& report, const std::set<Label>& crossing)
{
    for (const auto& [tissue, check] : report.tissues)
        if (crossing.count(tissue) == 0) check_sign(log, tissue, check);
}

void check_edges(DefectLog& log, const std::vector<Triangle>& merged, const std::vector<char>& skip,
                 CheckReport& report)
{
    const InterfaceComplex& complex = log.complex();
    const auto for_each_edge = [&](auto action) {
        for (std::uint32_t t = 0; t < merged.size(); ++t)
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t a = merged[t][k], b = merged[t][(k + 1) % 3];
                if (a != b) action(std::min(a, b), std::max(a, b), t);
            }
    };
    // Every edge use, (higher end, triangle), filed by the lower end.
    std::vector<std::uint32_t> sizes(complex.vertices.size(), 0);
    for_each_edge([&](std::uint32_t low, std::uint32_t, std::uint32_t) { ++sizes[low]; });
    const std::vector<std::uint32_t> start = bucket_starts(complex.vertices.size(), sizes);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> uses(start.back());
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for_each_edge([&](std::uint32_t low, std::uint32_t high, std::uint32_t t) { uses[next[low]++] = {high, t}; });
    sort_buckets(uses, start, std::less<>());
    report.edges = 0;
    report.junction_edges = 0;
    std::vector<FanBlade> blades;
    std::vector<std::uint32_t> fan;
    for (std::uint32_t v = 0; v + 1 < start.size(); ++v)
        for (std::uint32_t begin = start[v], end = start[v]; begin < start[v + 1]; begin = end) {
            while (end < start[v + 1] && uses[end].first == uses[begin].first) ++end;
            ++report.edges;
            if (end - begin < 3) continue;
            ++report.junction_edges;
            const std::uint32_t w = uses[begin].first;
            blades.clear();
            fan.clear();
            for (std::uint32_t i = begin; i < end; ++i) {
                const std::uint32_t t = uses[i].second;
                if (skip[t]) continue;
                blades.push_back(blade_on(merged[t], v, w, complex.vertices, complex.sides[t]));
                fan.push_back(t);
            }
            if (blades.size() < 3 ||
                fan_order(complex.vertices[v], complex.vertices[w], blades) != FanOrder::out_of_order)
                continue;
            log.add(DefectKind::tangled_junction, [&] {
                Defect defect;
                defect.location_mm = 0.5 * (complex.vertices[v] + complex.vertices[w]);
                defect.triangles = fan;
                for (const std::uint32_t t : fan)
                    defect.tissues.insert(defect.tissues.end(), {complex.sides[t].from, complex.sides[t].to});
                std::sort(defect.tissues.begin(), defect.tissues.end());
                defect.tissues.erase(std::unique(defect.tissues.begin(), defect.tissues.end()), defect.tissues.end());
                std::string names;
                for (const std::uint32_t t : fan) names += concat(names.empty() ? "" : ", ", log.triangle(t));
                defect.description =
                    concat("tangled junction edge ", v, '-', w, ": its ", fan.size(), " triangles (", names,
                           ") turn about it in an order their tissues contradict, a pocket turned "
                           "inside out ",
                           DefectLog::near(defect.location_mm));
                return defect;
            });
        }
}

} // namespace tissuemesh::surface::detail

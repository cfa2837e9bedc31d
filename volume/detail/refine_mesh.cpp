#include "volume/detail/refine_mesh.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <optional>

#include "core/node_tets.h"
#include "core/error.h"
#include "volume/detail/insert_node.h"
#include "volume/detail/smooth_node.h"
#include "volume/detail/tet_quality.h"
#include "volume/detail/tetgen_adapter.h"
#include "volume/detail/work_mesh.h"

namespace tissuemesh::volume::detail {
namespace {

constexpr double cone_tolerance = -1e-9; // a direction on a corner's boundary still counts as inside

std::vector<double> flatten(const std::vector<Vec3>& points)
{
    std::vector<double> flat;
    flat.reserve(3 * points.size());
    for (const Vec3& p : points) flat.insert(flat.end(), p.begin(), p.end());
    return flat;
}

Vec3 point_at(const std::vector<double>& flat, int index)
{
    return {flat[3 * index], flat[3 * index + 1], flat[3 * index + 2]};
}

/// TetGen's tets as positively oriented Tets over `vertices`.
std::vector<Tet> oriented(const TetgenOutput& out, const std::vector<Vec3>& vertices)
{
    std::vector<Tet> tets;
    tets.reserve(out.tets.size());
    for (const auto& t : out.tets) {
        Tet tet{static_cast<std::uint32_t>(t[0]), static_cast<std::uint32_t>(t[1]), static_cast<std::uint32_t>(t[2]),
                static_cast<std::uint32_t>(t[3])};
        const Vec3& a = vertices[tet[0]];
        if (dot(vertices[tet[1]] - a, cross(vertices[tet[2]] - a, vertices[tet[3]] - a)) < 0) std::swap(tet[2], tet[3]);
        tets.push_back(tet);
    }
    return tets;
}

/// How deep direction `d` from node `v` lies in the corner of old tet `t` at `v`: the smallest of its
/// coordinates along the tet's three edges from `v` (>= 0 inside the corner).
double corner_depth(const TetMesh& mesh, std::uint32_t t, std::uint32_t v, const Vec3& d)
{
    std::array<Vec3, 3> edge;
    int e = 0;
    for (const std::uint32_t w : mesh.tets[t])
        if (w != v) edge[e++] = mesh.vertices[w] - mesh.vertices[v];
    const double whole = dot(edge[0], cross(edge[1], edge[2]));
    if (whole == 0) return -std::numeric_limits<double>::infinity();
    const double a = dot(d, cross(edge[1], edge[2])) / whole, b = dot(edge[0], cross(d, edge[2])) / whole,
                 c = dot(edge[0], cross(edge[1], d)) / whole;
    return std::min({a, b, c}) / (std::abs(a) + std::abs(b) + std::abs(c));
}

/// The old tet whose corner at node `v` holds the direction towards `target`, or -1.
std::int64_t old_tet_towards(const TetMesh& mesh, const NodeTets& around, std::uint32_t v, const Vec3& target)
{
    const Vec3 d = target - mesh.vertices[v];
    std::int64_t best = -1;
    double best_depth = cone_tolerance;
    for (std::size_t k = around.offsets[v]; k < around.offsets[v + 1]; ++k) {
        const double depth = corner_depth(mesh, around.tets[k], v, d);
        if (depth >= best_depth) best_depth = depth, best = around.tets[k];
    }
    return best;
}

} // namespace

std::vector<Tet> delaunay_tets(const std::vector<Vec3>& points)
{
    const TetgenOutput out = run_tetgen({flatten(points), {}, {}, "zQ"});
    return oriented(out, points);
}

TetMesh insert_constrained(const TetMesh& mesh, const std::vector<Vec3>& points,
                           const std::vector<std::uint32_t>& source_tets)
{
    TetgenInput input;
    input.points = flatten(mesh.vertices);
    const std::vector<double> added = flatten(points);
    input.points.insert(input.points.end(), added.begin(), added.end());
    for (const Triangle& face : mesh.faces)
        input.triangles.push_back({static_cast<int>(face[0]), static_cast<int>(face[1]), static_cast<int>(face[2])});
    // p: a PLC (the faces); Y: no Steiner point on them; M: no merging of coplanar faces; z: zero-based.
    input.switches = "pzQMY";
    const TetgenOutput out = run_tetgen(input);

    TetMesh result;
    result.names = mesh.names, result.faces = mesh.faces, result.face_sides = mesh.face_sides;
    for (int v = 0; v < static_cast<int>(out.points.size() / 3); ++v)
        result.vertices.push_back(point_at(out.points, v));
    const std::size_t old_nodes = mesh.vertices.size(), placed = old_nodes + points.size();
    const NodeTets around = node_tets(mesh);
    const std::vector<Tet> tets = oriented(out, result.vertices);
    // Each new tet's old tet (its tissue), side by side: -1 in a hole of the old mesh, -2 for a tet of Steiner
    // points only.
    constexpr std::int64_t unknown = -2;
    std::vector<std::int64_t> sources(tets.size());
    const auto count = static_cast<std::int64_t>(tets.size());
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < count; ++i) {
        const Tet& tet = tets[static_cast<std::size_t>(i)];
        std::int64_t source = -1;
        bool any_known = false;
        for (const std::uint32_t v : tet) {
            if (v >= old_nodes && v < placed) source = source_tets[v - old_nodes], any_known = true;
            if (source >= 0) break;
            if (v >= old_nodes) continue;
            any_known = true;
            const Vec3 centroid = 0.25 * (result.vertices[tet[0]] + result.vertices[tet[1]] + result.vertices[tet[2]] +
                                          result.vertices[tet[3]]);
            source = old_tet_towards(mesh, around, v, centroid);
        }
        sources[static_cast<std::size_t>(i)] = any_known ? source : unknown;
    }
    if (std::find(sources.begin(), sources.end(), unknown) != sources.end())
        throw AlgorithmError("TetGen made a tetrahedron of Steiner points only while refining; its tissue is unknown. "
                             "Refine with a smaller --batch, or remesh with tm-tetra");
    for (std::size_t i = 0; i < tets.size(); ++i) {
        if (sources[i] < 0) continue; // in a hole of the old mesh
        result.tets.push_back(tets[i]);
        result.tet_labels.push_back(mesh.tet_labels[static_cast<std::size_t>(sources[i])]);
    }
    return result;
}

TetMesh insert_in_cavities(const TetMesh& mesh, const std::vector<Vec3>& points,
                           const std::vector<std::uint32_t>& source_tets, const std::function<bool(const Vec3&)>& clear)
{
    // A cavity whose new tets are worse than 10 degrees and than the tets it replaces has its node moved, and is
    // undone when that does not lift them.
    const double sliver_sine = sine_of_deg(10);
    WorkMesh work(mesh);
    // Smoothing asks the reference surface only about nodes on interfaces; every new node is inside a tissue.
    const SurfaceReference reference({}, {}, {});
    for (std::size_t k = 0; k < points.size(); ++k) {
        // The walk to the tet holding the point starts from its old tet, or, where an earlier cavity took that, from
        // a tet of the old tet's tissue at one of its nodes (nodes stay).
        const std::uint32_t source = source_tets[k];
        const Tet& old = mesh.tets[source];
        std::optional<std::uint32_t> start;
        if (work.alive(source) && work.tet(source) == old) start = source;
        for (std::size_t c = 0; c < 4 && !start; ++c)
            for (const std::uint32_t t : work.tets_of(old[c]))
                if (work.label(t) == mesh.tet_labels[source]) {
                    start = t;
                    break;
                }
        const std::size_t mark = work.mark();
        const std::optional<std::uint32_t> node = start ? insert_in_cavity(work, *start, points[k]) : std::nullopt;
        if (!node) continue; // nothing changed
        WorkMesh::Balance balance = work.balance_since(mark);
        if (balance.after < std::min(balance.before, sliver_sine)) {
            // A point near a face of its cavity's boundary makes a flat tet with it: the node moved to raise its
            // tets' smallest sine (it is inside a tissue, so it moves freely).
            smooth_node(work, *node, reference, 0);
            balance = work.balance_since(mark);
        }
        if (balance.after < std::min(balance.before, sliver_sine) || (clear && !clear(work.point(*node)))) {
            work.rollback(mark);
            continue;
        }
        work.commit();
    }
    TetMesh result = work.result();
    result.faces = mesh.faces, result.face_sides = mesh.face_sides;
    return result;
}

void drop_unused_nodes(TetMesh& mesh)
{
    constexpr std::uint32_t unused = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> new_index(mesh.vertices.size(), unused);
    for (const Tet& tet : mesh.tets)
        for (const std::uint32_t v : tet) new_index[v] = 0;
    std::uint32_t next = 0;
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
        if (new_index[v] != unused) mesh.vertices[next] = mesh.vertices[v], new_index[v] = next++;
    mesh.vertices.resize(next);
    for (Tet& tet : mesh.tets)
        for (std::uint32_t& v : tet) v = new_index[v];
    for (Triangle& face : mesh.faces)
        for (std::uint32_t& v : face) v = new_index[v];
}

} // namespace tissuemesh::volume::detail

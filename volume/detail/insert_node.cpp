#include "volume/detail/insert_node.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "volume/detail/flips.h"
#include "volume/detail/smooth_node.h"
#include "volume/detail/tetgen_adapter.h"

namespace tissuemesh::volume::detail {
namespace {

constexpr std::size_t max_cavity = 48; ///< tets in a Delaunay cavity at most
constexpr int max_walk = 64;           ///< steps of the walk to the tet holding the point
/// A candidate that raises the local smallest sine by this much is taken without trying the rest. On the 1 mm
/// usc19-5 head, a third fewer candidates were tried, and the best of all would have been better by 0.0065 in
/// sine on average.
constexpr double enough_gain = 0.1;
/// A new node keeps at least this fraction of the local size (WorkMesh::scale(): the shortest edge of the mesh
/// on entry at the bad tet's nodes, inherited by the new node) from every node it is joined to. Without it,
/// insertions repeated at one place left clusters of nodes microns apart (torso at 3 mm: edges of 6 um,
/// radius-edge 2153), whose tets are well shaped but needlessly tiny; a fraction of the bad tet's own edges
/// shrinks with each insertion, and one of its longest edge refused the splits that mend thin layers.
constexpr double min_edge_fraction = 0.3;

bool holds_all(const Tet& tet, const std::vector<std::uint32_t>& nodes)
{
    return std::all_of(nodes.begin(), nodes.end(),
                       [&](std::uint32_t v) { return std::find(tet.begin(), tet.end(), v) != tet.end(); });
}

Tet replaced(Tet tet, std::uint32_t old_node, std::uint32_t new_node)
{
    for (std::uint32_t& v : tet)
        if (v == old_node) v = new_node;
    return tet;
}

bool positive_with(const WorkMesh& mesh, const Tet& tet, std::uint32_t node, const Vec3& p)
{
    TetCorners c = mesh.corners(tet);
    for (int i = 0; i < 4; ++i)
        if (tet[i] == node) c[i] = p;
    return positive(c[0], c[1], c[2], c[3]);
}

/// Centre and squared radius of the circumsphere (doubles; a flat tet gives an infinite radius).
std::pair<Vec3, double> circumsphere(const TetCorners& p)
{
    const Vec3 a = p[1] - p[0], b = p[2] - p[0], c = p[3] - p[0];
    const double det = 2 * dot(a, cross(b, c));
    if (det == 0) return {p[0], std::numeric_limits<double>::infinity()};
    const Vec3 offset = (1.0 / det) * (dot(a, a) * cross(b, c) + dot(b, b) * cross(c, a) + dot(c, c) * cross(a, b));
    return {p[0] + offset, dot(offset, offset)};
}

/// The tet of t's tissue holding p strictly, walking from t across faces that are no constraint faces.
std::optional<std::uint32_t> locate(const WorkMesh& mesh, std::uint32_t t, const Vec3& p)
{
    for (int step = 0; step < max_walk; ++step) {
        const Tet& tet = mesh.tet(t);
        int beyond = -1;
        bool on_face = false;
        for (int i = 0; i < 4 && beyond < 0; ++i) {
            TetCorners c = mesh.corners(tet);
            c[i] = p;
            const int side = exact_side(c[0], c[1], c[2], c[3]);
            if (side < 0) beyond = i;
            on_face = on_face || side == 0;
        }
        if (beyond < 0) return on_face ? std::nullopt : std::optional<std::uint32_t>(t);
        if (mesh.face_with(tet[(beyond + 1) % 4], tet[(beyond + 2) % 4], tet[(beyond + 3) % 4])) return std::nullopt;
        const std::optional<std::uint32_t> next = mesh.tet_across(t, beyond);
        if (!next || mesh.label(*next) != mesh.label(t)) return std::nullopt;
        t = *next;
    }
    return std::nullopt;
}

/// The cavity's boundary: (cavity tet, corner) pairs whose opposite face the cavity does not share.
std::vector<std::pair<std::uint32_t, int>> cavity_boundary(const WorkMesh& mesh,
                                                           const std::vector<std::uint32_t>& cavity)
{
    std::vector<std::pair<std::uint32_t, int>> boundary;
    for (const std::uint32_t u : cavity)
        for (int i = 0; i < 4; ++i) {
            const std::optional<std::uint32_t> n = mesh.tet_across(u, i);
            if (!n || std::find(cavity.begin(), cavity.end(), *n) == cavity.end()) boundary.push_back({u, i});
        }
    return boundary;
}

/// Whether the boundary faces make one closed surface of a sphere's Euler characteristic holding every node of
/// the cavity (no node swallowed, no pinched edge).
bool sphere_boundary(const WorkMesh& mesh, const std::vector<std::uint32_t>& cavity,
                     const std::vector<std::pair<std::uint32_t, int>>& boundary)
{
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
    std::vector<std::uint32_t> nodes;
    for (const auto& [u, i] : boundary) {
        const Tet& tet = mesh.tet(u);
        for (int k = 1; k < 4; ++k) {
            const std::uint32_t v = tet[(i + k) % 4], w = tet[(i + k % 3 + 1) % 4];
            ++edges[std::minmax(v, w)];
            nodes.push_back(v);
        }
    }
    for (const auto& [edge, count] : edges)
        if (count != 2) return false;
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    for (const std::uint32_t u : cavity)
        for (const std::uint32_t v : mesh.tet(u))
            if (!std::binary_search(nodes.begin(), nodes.end(), v)) return false;
    const auto euler = static_cast<std::int64_t>(nodes.size()) - static_cast<std::int64_t>(edges.size()) +
                       static_cast<std::int64_t>(boundary.size());
    return euler == 2;
}

} // namespace

std::optional<std::uint32_t> split_simplex(WorkMesh& mesh, const std::vector<std::uint32_t>& simplex, const Vec3& p)
{
    // A face or edge of frozen nodes may be one a mesh part shares with the rest.
    if (std::all_of(simplex.begin(), simplex.end(), [&](std::uint32_t v) { return mesh.frozen(v); }))
        return std::nullopt;
    std::vector<std::uint32_t> holding, faces;
    for (const std::uint32_t t : mesh.tets_of(simplex[0]))
        if (holds_all(mesh.tet(t), simplex)) holding.push_back(t);
    for (const std::uint32_t f : mesh.faces_of(simplex[0])) {
        const Triangle& c = mesh.face(f).corners;
        if (holds_all({c[0], c[1], c[2], c[0]}, simplex)) faces.push_back(f);
    }
    if (holding.empty()) return std::nullopt;
    const auto m = static_cast<std::uint32_t>(mesh.node_count());
    std::vector<std::pair<Tet, Label>> made;
    for (const std::uint32_t t : holding)
        for (const std::uint32_t s : simplex) {
            const Tet tet = replaced(mesh.tet(t), s, m);
            if (!positive_with(mesh, mesh.tet(t), s, p)) return std::nullopt;
            made.push_back({tet, mesh.label(t)});
        }
    mesh.add_node(p);
    for (const std::uint32_t t : holding) mesh.remove_tet(t);
    for (const auto& [tet, label] : made) mesh.add_tet(tet, label);
    for (const std::uint32_t f : faces) {
        const ConstraintFace face = mesh.face(f);
        mesh.remove_face(f);
        for (const std::uint32_t s : simplex) {
            const Triangle& c = face.corners;
            if (c[0] != s && c[1] != s && c[2] != s) continue;
            mesh.add_face({c[0] == s ? m : c[0], c[1] == s ? m : c[1], c[2] == s ? m : c[2]}, face.sides, face.listed);
        }
    }
    mesh.classify(m);
    return m;
}

std::optional<std::uint32_t> insert_in_cavity(WorkMesh& mesh, std::uint32_t t, const Vec3& p)
{
    const std::optional<std::uint32_t> start = locate(mesh, t, p);
    if (!start) return std::nullopt;
    const Label label = mesh.label(*start);
    std::vector<std::uint32_t> cavity{*start};
    for (std::size_t k = 0; k < cavity.size() && cavity.size() < max_cavity; ++k)
        for (int i = 0; i < 4; ++i) {
            const Tet& tet = mesh.tet(cavity[k]);
            const std::optional<std::uint32_t> n = mesh.tet_across(cavity[k], i);
            if (!n || mesh.label(*n) != label || std::find(cavity.begin(), cavity.end(), *n) != cavity.end()) continue;
            if (mesh.face_with(tet[(i + 1) % 4], tet[(i + 2) % 4], tet[(i + 3) % 4])) continue;
            const auto [centre, radius2] = circumsphere(mesh.corners(*n));
            const Vec3 offset = p - centre;
            if (dot(offset, offset) < radius2 * (1 - 1e-9) && cavity.size() < max_cavity) cavity.push_back(*n);
        }
    // Shrink until every boundary face sees p: the tet of the face and p replaces the cavity tet's corner.
    std::vector<std::pair<std::uint32_t, int>> boundary;
    for (;;) {
        boundary = cavity_boundary(mesh, cavity);
        const auto blind = std::find_if(boundary.begin(), boundary.end(), [&](const auto& b) {
            return !positive_with(mesh, mesh.tet(b.first), mesh.tet(b.first)[static_cast<std::size_t>(b.second)], p);
        });
        if (blind == boundary.end()) break;
        if (blind->first == *start) return std::nullopt;
        cavity.erase(std::find(cavity.begin(), cavity.end(), blind->first));
    }
    if (!sphere_boundary(mesh, cavity, boundary)) return std::nullopt;
    const std::uint32_t m = mesh.add_node(p);
    std::vector<Tet> made;
    for (const auto& [u, i] : boundary)
        made.push_back(replaced(mesh.tet(u), mesh.tet(u)[static_cast<std::size_t>(i)], m));
    for (const std::uint32_t u : cavity) mesh.remove_tet(u);
    for (const Tet& tet : made) mesh.add_tet(tet, label);
    return m;
}

namespace {

/// A place to insert a node for a bad tet: a simplex of it to split at p, or (empty simplex) a cavity at p.
struct Candidate {
    std::vector<std::uint32_t> simplex;
    Vec3 p;
};

/// The point on the reference surface for a split of the constraint faces holding `nodes` near p: on their
/// patch when they are the two faces of one tissue pair, on their junction curve when three or more meet.
std::optional<Vec3> on_reference(const WorkMesh& mesh, const std::vector<std::uint32_t>& nodes, const Vec3& p,
                                 const SurfaceReference& reference, double reach)
{
    std::vector<std::uint32_t> faces;
    std::vector<Label> tissues;
    for (const std::uint32_t f : mesh.faces_of(nodes[0])) {
        const Triangle& c = mesh.face(f).corners;
        if (!holds_all({c[0], c[1], c[2], c[0]}, nodes)) continue;
        faces.push_back(f);
        tissues.push_back(mesh.face(f).sides.from), tissues.push_back(mesh.face(f).sides.to);
    }
    std::sort(tissues.begin(), tissues.end());
    tissues.erase(std::unique(tissues.begin(), tissues.end()), tissues.end());
    if (faces.size() >= 3) return reference.onto_curve(p, tissues, reach);
    if (tissues.size() != 2 || (nodes.size() == 2 && faces.size() != 2)) return std::nullopt;
    return reference.onto_patch(p, tissues[0], tissues[1], reach);
}

std::vector<Candidate> candidates(const WorkMesh& mesh, std::uint32_t t, const SurfaceReference& reference,
                                  bool on_interfaces)
{
    const Tet tet = mesh.tet(t);
    const TetCorners c = mesh.corners(t);
    std::vector<Candidate> found;
    for (const auto& e : edge_corners) {
        const std::vector<std::uint32_t> edge{tet[e[0]], tet[e[1]]};
        const Vec3 middle = 0.5 * (c[e[0]] + c[e[1]]);
        if (!mesh.constrained_edge(edge[0], edge[1])) found.push_back({edge, middle});
        else if (on_interfaces)
            if (const auto p = on_reference(mesh, edge, middle, reference, distance(c[e[0]], c[e[1]])))
                found.push_back({edge, *p});
    }
    for (int i = 0; i < 4; ++i) {
        const std::vector<std::uint32_t> face{tet[(i + 1) % 4], tet[(i + 2) % 4], tet[(i + 3) % 4]};
        const Vec3 centre = (1.0 / 3) * (c[(i + 1) % 4] + c[(i + 2) % 4] + c[(i + 3) % 4]);
        if (!mesh.face_with(face[0], face[1], face[2])) found.push_back({face, centre});
        else if (on_interfaces)
            if (const auto p = on_reference(mesh, face, centre, reference, distance(centre, c[i])))
                found.push_back({face, *p});
    }
    // A cap on an interface (two of its faces constraint faces meeting at an edge, bent little): a cavity at a
    // point inside the tissue above that edge, so that each of the two faces gets a tet of its own.
    for (const auto& e : edge_corners) {
        const std::uint32_t u = tet[e[0]], w = tet[e[1]];
        if (!mesh.face_with(u, w, tet[e[2]]) || !mesh.face_with(u, w, tet[e[3]])) continue;
        Vec3 inward{0, 0, 0};
        for (const int k : {e[2], e[3]}) {
            // The face opposite corner k (holding the edge and the other corner) and its normal towards k.
            const int other = k == e[2] ? e[3] : e[2];
            Vec3 n = cross(c[e[1]] - c[e[0]], c[other] - c[e[0]]);
            if (dot(n, c[k] - c[e[0]]) < 0) n = -1.0 * n;
            if (norm(n) > 0) inward = inward + (1.0 / norm(n)) * n;
        }
        if (norm(inward) == 0) continue;
        const double length = distance(c[e[0]], c[e[1]]);
        found.push_back({{}, 0.5 * (c[e[0]] + c[e[1]]) + (0.3 * length / norm(inward)) * inward});
    }
    // Delaunay cavities at the centroid and, when it is not far off, the circumcentre.
    const Vec3 centroid = 0.25 * (c[0] + c[1] + c[2] + c[3]);
    found.push_back({{}, centroid});
    const auto [centre, radius2] = circumsphere(c);
    if (std::isfinite(radius2) && distance(centre, centroid) < 2 * std::sqrt(radius2)) found.push_back({{}, centre});
    return found;
}

/// Whether an edge at node v is shorter than `length`.
bool has_edge_shorter_than(const WorkMesh& mesh, std::uint32_t v, double length)
{
    for (const std::uint32_t u : mesh.tets_of(v))
        for (const std::uint32_t w : mesh.tet(u))
            if (w != v && distance(mesh.point(w), mesh.point(v)) < length) return true;
    return false;
}

/// Applies a candidate, then mends the new node's star: its node smoothed, and the tets around it still no
/// better than `bar` flipped where that helps (twice). Whether t is gone, a node was made and none of its edges is
/// shorter than min_edge_fraction of the local size.
bool apply(WorkMesh& mesh, std::uint32_t t, const Candidate& candidate, const SurfaceReference& reference, double bar,
           double face_tolerance_mm)
{
    double scale = std::numeric_limits<double>::infinity();
    for (const std::uint32_t v : mesh.tet(t)) scale = std::min(scale, mesh.scale(v));
    const std::optional<std::uint32_t> node = candidate.simplex.empty()
                                                  ? insert_in_cavity(mesh, t, candidate.p)
                                                  : split_simplex(mesh, candidate.simplex, candidate.p);
    if (!node || mesh.alive(t)) return false;
    mesh.set_scale(*node, scale);
    for (const std::uint32_t f : mesh.faces_of(*node)) {
        const ConstraintFace& face = mesh.face(f);
        const Triangle& c = face.corners;
        if (!reference.holds_triangle(mesh.point(c[0]), mesh.point(c[1]), mesh.point(c[2]), face.sides.from,
                                      face.sides.to, face_tolerance_mm))
            return false;
    }
    smooth_node(mesh, *node, reference, face_tolerance_mm);
    for (int round = 0; round < 2; ++round) {
        bool flipped = false;
        const std::vector<std::uint32_t> around = mesh.tets_of(*node);
        for (const std::uint32_t u : around) {
            if (!mesh.alive(u) || mesh.quality(u) > bar) continue;
            const Tet tet = mesh.tet(u);
            bool done = false;
            for (const auto& e : edge_corners)
                if (!done && remove_edge(mesh, tet[e[0]], tet[e[1]])) done = true;
            for (int i = 0; i < 4 && !done; ++i)
                if (remove_faces(mesh, u, i)) done = true;
            flipped = flipped || done;
        }
        if (!flipped || mesh.tets_of(*node).empty()) break;
        smooth_node(mesh, *node, reference, face_tolerance_mm);
    }
    return !has_edge_shorter_than(mesh, *node, min_edge_fraction * scale);
}

} // namespace

bool insert_for_tet(WorkMesh& mesh, std::uint32_t t, const SurfaceReference& reference, bool on_interfaces,
                    double face_tolerance_mm, const std::function<bool(std::size_t mark)>& kept)
{
    const std::vector<Candidate> tries = candidates(mesh, t, reference, on_interfaces);
    const double bar = mesh.quality(t) + 0.05; // tets around the new node this bad are worth a flip
    const auto applied = [&](const Candidate& candidate, std::size_t mark) {
        return apply(mesh, t, candidate, reference, bar, face_tolerance_mm) && (!kept || kept(mark));
    };
    std::size_t best = tries.size();
    double best_gain = 0;
    for (std::size_t k = 0; k < tries.size(); ++k) {
        const std::size_t mark = mesh.mark();
        if (applied(tries[k], mark)) {
            const WorkMesh::Balance balance = mesh.balance_since(mark);
            if (balance.after - balance.before > best_gain) best_gain = balance.after - balance.before, best = k;
            // Enough gain is kept as it is: the best of all candidates would add little to it.
            if (best == k && best_gain >= enough_gain) return true;
        }
        mesh.rollback(mark);
    }
    if (best == tries.size()) return false;
    const std::size_t mark = mesh.mark();
    if (applied(tries[best], mark)) return true;
    mesh.rollback(mark);
    return false;
}

} // namespace tissuemesh::volume::detail

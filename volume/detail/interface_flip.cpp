#include "volume/detail/interface_flip.h"

#include <algorithm>
#include <limits>
#include <optional>
#include <unordered_set>
#include <vector>

#include "volume/detail/ring_triangulation.h"
#include "volume/detail/tetgen_adapter.h"

namespace tissuemesh::volume::detail {
namespace {

/// One side of the interface: the ring's nodes from one apex to the other, and its tets' tissue.
struct Side {
    std::vector<std::uint32_t> polygon;
    Label label = 0;
    std::vector<Tet> made;
};

/// The constraint faces on edge ab.
std::vector<std::uint32_t> faces_on(const WorkMesh& mesh, std::uint32_t a, std::uint32_t b)
{
    std::vector<std::uint32_t> found;
    for (const std::uint32_t f : mesh.faces_of(a)) {
        const Triangle& c = mesh.face(f).corners;
        if (c[0] == b || c[1] == b || c[2] == b) found.push_back(f);
    }
    return found;
}

std::uint32_t third(const Triangle& t, std::uint32_t a, std::uint32_t b)
{
    for (const std::uint32_t v : t)
        if (v != a && v != b) return v;
    return a;
}

Vec3 normal(const WorkMesh& mesh, const Triangle& t)
{
    return cross(mesh.point(t[1]) - mesh.point(t[0]), mesh.point(t[2]) - mesh.point(t[0]));
}

/// The new face on (x, y, z) turned so that its normal points from `sides.from` into `sides.to`, judged by a new tet
/// holding it: its fourth node lies behind the face when the tet is of `from`, in front when of `to`.
Triangle oriented(const WorkMesh& mesh, Triangle face, const LabelPair& sides, const std::vector<Side>& parts)
{
    for (const Side& part : parts)
        for (const Tet& tet : part.made) {
            const auto holds = [&](std::uint32_t v) { return std::find(tet.begin(), tet.end(), v) != tet.end(); };
            if (!holds(face[0]) || !holds(face[1]) || !holds(face[2])) continue;
            std::uint32_t w = 0;
            for (const std::uint32_t v : tet)
                if (v != face[0] && v != face[1] && v != face[2]) w = v;
            const int side = exact_side(mesh.point(face[0]), mesh.point(face[1]), mesh.point(face[2]), mesh.point(w));
            const bool behind = part.label == sides.from;
            if ((side > 0) == behind) std::swap(face[1], face[2]);
            return face;
        }
    return face;
}

/// Whether the tets beyond the faces of `flat` opposite its nodes a and b (both of its tissue) are linked through
/// tets of that tissue without `flat`: a search across shared faces, over at most `budget` tets (not found within
/// it counts as not linked).
bool linked_without(const WorkMesh& mesh, std::uint32_t flat, std::uint32_t a, std::uint32_t b,
                    std::size_t budget = 20000)
{
    const Tet& tet = mesh.tet(flat);
    const auto corner = [&](std::uint32_t v) {
        return static_cast<int>(std::find(tet.begin(), tet.end(), v) - tet.begin());
    };
    const std::optional<std::uint32_t> from = mesh.tet_across(flat, corner(b)), to = mesh.tet_across(flat, corner(a));
    const Label label = mesh.label(flat);
    if (!from || !to || mesh.label(*from) != label || mesh.label(*to) != label) return false;
    std::unordered_set<std::uint32_t> seen{flat, *from};
    std::vector<std::uint32_t> queue{*from};
    for (std::size_t next = 0; next < queue.size() && queue.size() < budget; ++next)
        for (int i = 0; i < 4; ++i) {
            const std::optional<std::uint32_t> across = mesh.tet_across(queue[next], i);
            if (!across || mesh.label(*across) != label) continue;
            if (*across == *to) return true;
            if (seen.insert(*across).second) queue.push_back(*across);
        }
    return false;
}

} // namespace

bool flip_interface_edge(WorkMesh& mesh, std::uint32_t a, std::uint32_t b, const SurfaceReference& reference,
                         double tolerance_mm, std::size_t max_ring)
{
    if (mesh.frozen(a) && mesh.frozen(b)) return false; // perhaps on a face a mesh part shares with the rest
    const std::vector<std::uint32_t> on_edge = faces_on(mesh, a, b);
    if (on_edge.size() != 2) return false;
    const ConstraintFace first = mesh.face(on_edge[0]), second = mesh.face(on_edge[1]);
    if (std::minmax(first.sides.from, first.sides.to) != std::minmax(second.sides.from, second.sides.to)) return false;
    const std::uint32_t c = third(first.corners, a, b), d = third(second.corners, a, b);
    if (c == d) return false;
    std::vector<std::uint32_t> ring, tets;
    bool open = false;
    if (!mesh.edge_ring(a, b, ring, tets, &open) || ring.size() > max_ring) return false;
    // cd may be an edge already only of the flat tet (a, b, c, d), one side's only tet: the flip removes it, and
    // its faces (a, c, d) and (b, c, d) become the interface, so they must not be constraint faces already.
    // (A tet with these four nodes has cd as an edge, so it is looked for only where cd is one.)
    const bool cd_exists = mesh.has_edge(c, d);
    const std::optional<std::uint32_t> flat = cd_exists ? mesh.tet_with(a, b, c, d) : std::nullopt;
    if (cd_exists && (!flat || mesh.face_with(a, c, d) || mesh.face_with(b, c, d))) return false;
    const auto at = [&](std::uint32_t v) {
        return static_cast<std::size_t>(std::find(ring.begin(), ring.end(), v) - ring.begin());
    };
    const std::size_t ic = at(c), id = at(d), n = ring.size();
    if (ic == n || id == n) return false;

    // The parts of the ring between the apexes, each of one tissue (an open ring runs from apex to apex).
    std::vector<Side> parts;
    auto take = [&](std::size_t from, std::size_t to) {
        Side side;
        for (std::size_t k = from;; k = (k + 1) % n) {
            side.polygon.push_back(ring[k]);
            if (k == to) break;
            if (side.polygon.size() == 1) side.label = mesh.label(tets[k]);
            if (mesh.label(tets[k]) != side.label) return false;
        }
        parts.push_back(std::move(side));
        return true;
    };
    if (open) {
        if (!((ic == 0 && id == n - 1) || (id == 0 && ic == n - 1)) || !take(0, n - 1)) return false;
    } else if (!take(ic, id) || !take(id, ic) || parts[0].label == parts[1].label) {
        return false;
    }
    double before = std::numeric_limits<double>::infinity();
    for (const std::uint32_t t : tets) before = std::min(before, mesh.quality(t));
    double after = std::numeric_limits<double>::infinity();
    for (Side& side : parts) {
        const RingTriangulation best(mesh, a, b, side.polygon, before);
        after = std::min(after, best.quality());
        if (!(after > before)) return false;
        std::vector<std::array<std::size_t, 3>> triangles;
        best.triangles(0, side.polygon.size() - 1, triangles);
        const std::size_t last = side.polygon.size() - 1;
        for (const auto& [i, k, j] : triangles) {
            for (const auto& [u, w] : {std::pair{i, k}, std::pair{k, j}, std::pair{i, j}})
                if (w - u >= 2 && !(u == 0 && w == last) && mesh.has_edge(side.polygon[u], side.polygon[w]))
                    return false;
            side.made.push_back({a, side.polygon[i], side.polygon[k], side.polygon[j]});
            side.made.push_back({b, side.polygon[i], side.polygon[j], side.polygon[k]});
        }
    }
    const Triangle new_a = oriented(mesh, {a, c, d}, first.sides, parts),
                   new_b = oriented(mesh, {b, d, c}, first.sides, parts);
    // The new faces stay on the patch and turn the way the old ones did (on the outer boundary no tet beyond
    // them would tell a fold); normals all taken from first.sides.from to first.sides.to.
    const Vec3 old_normal = normal(mesh, first.corners) +
                            (second.sides.from == first.sides.from ? 1.0 : -1.0) * normal(mesh, second.corners);
    for (const Triangle& face : {new_a, new_b}) {
        if (dot(normal(mesh, face), old_normal) <= 0) return false;
        if (!reference.holds_triangle(mesh.point(face[0]), mesh.point(face[1]), mesh.point(face[2]), first.sides.from,
                                      first.sides.to, tolerance_mm))
            return false;
    }
    // A flat tet that goes may be its tissue's only link between the tets beyond its faces (a, c, d) and (b, c, d):
    // else the tissue would fall into pieces.
    if (flat && !linked_without(mesh, *flat, a, b)) return false;
    for (const std::uint32_t t : tets) mesh.remove_tet(t);
    for (const Side& side : parts)
        for (const Tet& tet : side.made) mesh.add_tet(tet, side.label);
    mesh.remove_face(on_edge[0]);
    mesh.remove_face(on_edge[1]);
    mesh.add_face(new_a, first.sides, first.listed || second.listed);
    mesh.add_face(new_b, first.sides, first.listed || second.listed);
    for (const std::uint32_t v : {a, b, c, d}) mesh.classify(v);
    return true;
}

} // namespace tissuemesh::volume::detail

#include "volume/detail/flips.h"

#include "volume/detail/ring_triangulation.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace tissuemesh::volume::detail {
namespace {

double worst_quality(const WorkMesh& mesh, const std::vector<std::uint32_t>& tets)
{
    double worst = std::numeric_limits<double>::infinity();
    for (const std::uint32_t t : tets) worst = std::min(worst, mesh.quality(t));
    return worst;
}

void replace(WorkMesh& mesh, const std::vector<std::uint32_t>& old_tets, const std::vector<Tet>& new_tets, Label label)
{
    for (const std::uint32_t t : old_tets) mesh.remove_tet(t);
    for (const Tet& tet : new_tets) mesh.add_tet(tet, label);
}

} // namespace

bool remove_edge(WorkMesh& mesh, std::uint32_t a, std::uint32_t b, std::size_t max_ring)
{
    if (mesh.constrained_edge(a, b)) return false;
    std::vector<std::uint32_t> ring, tets;
    if (!mesh.edge_ring(a, b, ring, tets) || ring.size() > max_ring) return false;
    const Label label = mesh.label(tets[0]);
    for (const std::uint32_t t : tets)
        if (mesh.label(t) != label) return false;
    const double before = worst_quality(mesh, tets);
    const RingTriangulation best(mesh, a, b, ring, before);
    if (!(best.quality() > before)) return false;
    std::vector<std::array<std::size_t, 3>> triangles;
    best.triangles(0, ring.size() - 1, triangles);
    // A diagonal of the polygon that is an edge elsewhere already would join the two places twice.
    for (const auto& [i, k, j] : triangles)
        for (const auto& [u, w] : {std::pair{i, k}, std::pair{k, j}, std::pair{i, j}})
            if (w - u >= 2 && !(u == 0 && w == ring.size() - 1) && mesh.has_edge(ring[u], ring[w])) return false;
    std::vector<Tet> new_tets;
    for (const auto& [i, k, j] : triangles) {
        new_tets.push_back({a, ring[i], ring[k], ring[j]});
        new_tets.push_back({b, ring[i], ring[j], ring[k]});
    }
    replace(mesh, tets, new_tets, label);
    return true;
}

bool remove_faces(WorkMesh& mesh, std::uint32_t t, int i, std::size_t max_ring)
{
    const Tet first = mesh.tet(t);
    const std::uint32_t a = first[static_cast<std::size_t>(i)];
    // (a, x, y, z) positive: the ring x, y, z turns counter-clockwise seen from b, beyond the face.
    std::uint32_t x = first[(i + 1) % 4], y = first[(i + 2) % 4], z = first[(i + 3) % 4];
    if (i % 2 == 1) std::swap(y, z); // an odd cyclic shift: restore the even order
    if (mesh.face_with(x, y, z)) return false;
    const std::optional<std::uint32_t> across = mesh.tet_across(t, i);
    if (!across || mesh.label(*across) != mesh.label(t)) return false;
    std::uint32_t b = 0;
    for (const std::uint32_t v : mesh.tet(*across))
        if (v != x && v != y && v != z) b = v;
    if (mesh.has_edge(a, b)) return false;
    const Label label = mesh.label(t);

    std::vector<std::uint32_t> ring{x, y, z}, removed{t, *across};
    std::vector<std::uint32_t> best_ring;
    std::vector<std::uint32_t> best_removed;
    double best_gain = 0;
    for (;;) {
        const double before = worst_quality(mesh, removed);
        // The new tets around ab, and the worst of them.
        double after = std::numeric_limits<double>::infinity();
        std::size_t worst = 0;
        for (std::size_t k = 0; k < ring.size(); ++k) {
            const double q = new_tet_quality(mesh, {a, b, ring[k], ring[(k + 1) % ring.size()]}, invalid);
            if (q < after) after = q, worst = k;
        }
        if (after - before > best_gain) best_gain = after - before, best_ring = ring, best_removed = removed;
        if (ring.size() >= max_ring) break;
        // Grow at the worst new tet: the face beyond its ring edge, if it too lies between a and b.
        const std::uint32_t r0 = ring[worst], r1 = ring[(worst + 1) % ring.size()];
        std::optional<std::uint32_t> upper, lower;
        std::uint32_t w = 0;
        for (const std::uint32_t u : mesh.tets_of(r0)) {
            const Tet& tet = mesh.tet(u);
            if (std::find(removed.begin(), removed.end(), u) != removed.end() || mesh.label(u) != label) continue;
            const bool has_r1 = std::find(tet.begin(), tet.end(), r1) != tet.end();
            const bool has_a = std::find(tet.begin(), tet.end(), a) != tet.end();
            if (!has_r1 || !has_a) continue;
            upper = u;
            for (const std::uint32_t v : tet)
                if (v != a && v != r0 && v != r1) w = v;
        }
        if (!upper || w == b || std::find(ring.begin(), ring.end(), w) != ring.end()) break;
        // Faces the growth removes: the one between a and b, and the two from the edge's old tets to the new ones.
        if (mesh.face_with(r0, r1, w) || mesh.face_with(a, r0, r1) || mesh.face_with(b, r0, r1)) break;
        lower = mesh.tet_with(b, r0, r1, w);
        if (!lower || mesh.label(*lower) != label) break;
        ring.insert(ring.begin() + static_cast<std::ptrdiff_t>(worst) + 1, w);
        removed.push_back(*upper), removed.push_back(*lower);
    }
    if (best_ring.empty()) return false;
    std::vector<Tet> new_tets;
    for (std::size_t k = 0; k < best_ring.size(); ++k)
        new_tets.push_back({a, b, best_ring[k], best_ring[(k + 1) % best_ring.size()]});
    replace(mesh, best_removed, new_tets, label);
    return true;
}

} // namespace tissuemesh::volume::detail

#include "fem/detail/incidence.h"

#include <algorithm>

namespace tissuemesh::fem::detail {

NodeTets node_tets(const TetMesh& mesh)
{
    NodeTets incidence;
    incidence.offsets.assign(mesh.vertex_count() + 1, 0);
    for (const Tet& tet : mesh.tets)
        for (std::uint32_t v : tet) ++incidence.offsets[v + 1];
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) incidence.offsets[v + 1] += incidence.offsets[v];
    incidence.tets.resize(incidence.offsets.back());
    // Filling in tet order leaves every node's list sorted.
    std::vector<std::size_t> next(incidence.offsets.begin(), incidence.offsets.end() - 1);
    for (std::size_t t = 0; t < mesh.tet_count(); ++t)
        for (std::uint32_t v : mesh.tets[t]) incidence.tets[next[v]++] = static_cast<std::uint32_t>(t);
    return incidence;
}

namespace {

bool holds(const Tet& tet, std::uint32_t v)
{
    return tet[0] == v || tet[1] == v || tet[2] == v || tet[3] == v;
}

// The tet other than `self` around the face (a, b, c): it is in the list of a and holds b and c. In a
// conforming mesh there is at most one.
std::uint32_t across(const TetMesh& mesh, const NodeTets& incidence, std::uint32_t self, std::uint32_t a,
                     std::uint32_t b, std::uint32_t c)
{
    for (std::size_t i = incidence.offsets[a]; i < incidence.offsets[a + 1]; ++i) {
        const std::uint32_t other = incidence.tets[i];
        if (other != self && holds(mesh.tets[other], b) && holds(mesh.tets[other], c)) return other;
    }
    return no_tet;
}

} // namespace

std::vector<std::uint32_t> face_neighbours(const TetMesh& mesh, const NodeTets& incidence)
{
    const auto count = static_cast<std::int64_t>(mesh.tet_count());
    std::vector<std::uint32_t> neighbours(4 * mesh.tet_count(), no_tet);
#pragma omp parallel for schedule(static)
    for (std::int64_t t = 0; t < count; ++t) {
        const Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
        for (int k = 0; k < 4; ++k) {
            const std::uint32_t a = tet[face_vertices[k][0]], b = tet[face_vertices[k][1]], c = tet[face_vertices[k][2]];
            // Scan the shortest of the three lists.
            const auto length = [&](std::uint32_t v) { return incidence.offsets[v + 1] - incidence.offsets[v]; };
            const std::uint32_t self = static_cast<std::uint32_t>(t);
            std::uint32_t other = no_tet;
            if (length(a) <= length(b) && length(a) <= length(c)) other = across(mesh, incidence, self, a, b, c);
            else if (length(b) <= length(c)) other = across(mesh, incidence, self, b, c, a);
            else other = across(mesh, incidence, self, c, a, b);
            neighbours[4 * static_cast<std::size_t>(t) + static_cast<std::size_t>(k)] = other;
        }
    }
    return neighbours;
}

} // namespace tissuemesh::fem::detail

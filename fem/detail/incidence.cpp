#include "fem/detail/incidence.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

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

std::vector<std::uint32_t> face_neighbours(const TetMesh& mesh)
{
    // Every tet face goes into the bucket of its smallest vertex (a counting sort), then each small bucket
    // is sorted by the other two vertices and equal neighbours are paired: passes over the faces, no search
    // through other tets per face. The buckets are filled in parallel with atomic cursors, so the order
    // inside a bucket varies from run to run; sorting by (middle, largest, slot) makes it unique again.
    struct Face {
        std::uint32_t middle, largest, slot;  ///< slot = 4 tet + k
    };
    const std::size_t nodes = mesh.vertex_count();
    const auto tets = static_cast<std::int64_t>(mesh.tet_count());
    const auto sorted_face = [&](std::size_t t, int k) {
        std::array<std::uint32_t, 3> v{mesh.tets[t][face_vertices[k][0]], mesh.tets[t][face_vertices[k][1]],
                                       mesh.tets[t][face_vertices[k][2]]};
        std::sort(v.begin(), v.end());
        return v;
    };
    std::vector<std::size_t> start(nodes + 1, 0);
#pragma omp parallel for schedule(static)
    for (std::int64_t t = 0; t < tets; ++t)
        for (int k = 0; k < 4; ++k) {
            const std::uint32_t smallest = sorted_face(static_cast<std::size_t>(t), k)[0];
#pragma omp atomic
            ++start[smallest + 1];
        }
    for (std::size_t v = 0; v < nodes; ++v) start[v + 1] += start[v];
    std::vector<Face> faces(start.back());
    std::vector<std::size_t> next(start.begin(), start.end() - 1);
#pragma omp parallel for schedule(static)
    for (std::int64_t t = 0; t < tets; ++t)
        for (int k = 0; k < 4; ++k) {
            const std::array<std::uint32_t, 3> v = sorted_face(static_cast<std::size_t>(t), k);
            std::size_t at = 0;
#pragma omp atomic capture
            at = next[v[0]]++;
            faces[at] = {v[1], v[2], static_cast<std::uint32_t>(4 * t + k)};
        }
    std::vector<std::uint32_t> neighbours(4 * mesh.tet_count(), no_tet);
    const auto count = static_cast<std::int64_t>(nodes);
#pragma omp parallel for schedule(dynamic, 1024)
    for (std::int64_t v = 0; v < count; ++v) {
        const auto begin = faces.begin() + static_cast<std::ptrdiff_t>(start[static_cast<std::size_t>(v)]);
        const auto end = faces.begin() + static_cast<std::ptrdiff_t>(start[static_cast<std::size_t>(v) + 1]);
        std::sort(begin, end, [](const Face& a, const Face& b) {
            return a.middle != b.middle ? a.middle < b.middle : a.largest != b.largest ? a.largest < b.largest : a.slot < b.slot;
        });
        for (auto face = begin; face != end; ++face) {
            const auto other = face + 1;
            if (other == end || other->middle != face->middle || other->largest != face->largest) continue;
            neighbours[face->slot] = other->slot / 4;
            neighbours[other->slot] = face->slot / 4;
            face = other;
        }
    }
    return neighbours;
}

} // namespace tissuemesh::fem::detail

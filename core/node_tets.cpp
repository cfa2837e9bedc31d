#include "core/node_tets.h"

namespace tissuemesh {

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

} // namespace tissuemesh

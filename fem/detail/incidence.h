// Node-to-tet incidence of a tet mesh, for assembly (the face-to-tet one is core/tet_adjacency.h).
#pragma once

#include <cstdint>
#include <vector>

#include "core/tet_mesh.h"

namespace tissuemesh::fem::detail {

/// The tets around every node in compressed rows: the tets of node v are
/// tets[offsets[v]] .. tets[offsets[v + 1] - 1], in increasing order (#V + 1 offsets, 4 #T tets).
struct NodeTets {
    std::vector<std::size_t> offsets;
    std::vector<std::uint32_t> tets;
};

/// @pre validate_indices(mesh) passes
NodeTets node_tets(const TetMesh& mesh);

} // namespace tissuemesh::fem::detail

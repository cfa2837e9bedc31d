// The tets around every node of a tet mesh (the face-to-tet adjacency is core/tet_adjacency.h): for assembly,
// refinement's point location and the mesh improver's rings of tets.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/tet_mesh.h"

namespace tissuemesh {

/// The tets around every node in compressed rows: the tets of node v are
/// tets[offsets[v]] .. tets[offsets[v + 1] - 1], in increasing order (#V + 1 offsets, 4 #T tets).
struct NodeTets {
    std::vector<std::size_t> offsets;
    std::vector<std::uint32_t> tets;
};

/// @pre validate_indices(mesh) passes
NodeTets node_tets(const TetMesh& mesh);

} // namespace tissuemesh

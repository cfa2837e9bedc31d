// Node-to-tet and face-to-tet incidence of a tet mesh, for assembly and the face loops.
#pragma once

#include <cstdint>
#include <vector>

#include "core/tet_mesh.h"
#include "core/tet_shape.h"

namespace tissuemesh::fem::detail {

/// The tets around every node in compressed rows: the tets of node v are
/// tets[offsets[v]] .. tets[offsets[v + 1] - 1], in increasing order (#V + 1 offsets, 4 #T tets).
struct NodeTets {
    std::vector<std::size_t> offsets;
    std::vector<std::uint32_t> tets;
};

/// @pre validate_indices(mesh) passes
NodeTets node_tets(const TetMesh& mesh);

/// No tet across the face (it is on the outer boundary).
inline constexpr std::uint32_t no_tet = 0xffffffffu;

/// The vertices of face k of a tet (the face opposite vertex k), right-hand normal outward: core's table.
inline constexpr const auto& face_vertices = tet_faces;

/// For face k of tet t, the other tet that holds it, or no_tet: entry 4 t + k (#T by 4). The result does
/// not depend on the thread count.
/// @pre validate_indices(mesh) passes
std::vector<std::uint32_t> face_neighbours(const TetMesh& mesh);

} // namespace tissuemesh::fem::detail

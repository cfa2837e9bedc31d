// Topological improvement of a tet mesh without moving or adding nodes: edge removal (3-2 and 4-4 flips as
// its smallest cases) and multi-face removal (the 2-3 flip as its smallest case), after Shewchuk's "Two
// discrete optimization algorithms for the topological improvement of tetrahedral meshes" (2002), as Stellar
// uses them. Neither ever removes a constraint face nor crosses one: tissues and interfaces stay as they are.
#pragma once

#include <cstdint>

#include "volume/detail/work_mesh.h"

namespace tissuemesh::volume::detail {

/// Removes edge ab: its ring of tets (all of one tissue, no constraint face on ab) is replaced by the
/// triangulation of the ring polygon, swept to a and to b, that maximises the smallest dihedral sine
/// (dynamic programming over the polygon). Done only when that smallest sine beats the ring's own, every new
/// tet is positive (exact) and no new edge exists already. Rings longer than `max_ring` are left.
/// @returns whether the edge was removed (an edit of `mesh`, journaled)
bool remove_edge(WorkMesh& mesh, std::uint32_t a, std::uint32_t b, std::size_t max_ring = 9);

/// Removes the face of tet t opposite its corner i, and greedily more faces sandwiched between the same two
/// apexes a (t's corner i) and b (the apex of the tet across): the tets on both sides of those faces are
/// replaced by the tets around the new edge ab. Done only when the smallest dihedral sine rises, every new tet
/// is positive and ab was no edge before. No constraint face is removed.
/// @returns whether faces were removed (an edit of `mesh`, journaled)
bool remove_faces(WorkMesh& mesh, std::uint32_t t, int i, std::size_t max_ring = 7);

} // namespace tissuemesh::volume::detail

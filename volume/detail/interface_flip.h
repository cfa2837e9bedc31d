// The 2-2 flip of an interface edge, with the tets on both sides remade: how the improver mends bad
// interface triangles (a small angle of an interface triangle bounds the dihedral angles of the tets on it)
// and flat tets lying on an interface, where the four nodes are (nearly) coplanar.
#pragma once

#include <cstdint>

#include "volume/detail/surface_reference.h"
#include "volume/detail/work_mesh.h"

namespace tissuemesh::volume::detail {

/// Flips interface edge ab, which two constraint faces (a, b, c) and (a, b, d) of one tissue pair hold (no
/// junction edge): they become (a, c, d) and (b, d, c), and on each side of the interface the tets around ab
/// are replaced by the best triangulation of that side's part of the ring, swept to a and b (edge removal on
/// each side, the new edge cd shared). A side with one tet only loses it to the other side: that is how a
/// flat tet lying on an interface goes. Done only when the smallest dihedral sine rises, every new tet is
/// positive (exact), the new faces lie within `tolerance_mm` of the reference patch
/// (SurfaceReference::holds_triangle) and turn the way the old ones did, and cd was no edge (or only one of the flat
/// tet (a, b, c, d), when it is its side's only tet, its faces (a, c, d) and (b, c, d) are no constraint faces, and
/// the tets beyond those faces stay linked in its tissue without it: no tissue falls into pieces).
/// @returns whether the edge was flipped (edits of `mesh`, journaled)
bool flip_interface_edge(WorkMesh& mesh, std::uint32_t a, std::uint32_t b, const SurfaceReference& reference,
                         double tolerance_mm, std::size_t max_ring = 10);

} // namespace tissuemesh::volume::detail

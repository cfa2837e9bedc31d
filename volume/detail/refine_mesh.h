// The Delaunay and constrained Delaunay rebuilds behind refine(): TetGen on the old nodes plus the new ones.
#pragma once

#include <cstdint>
#include <vector>

#include "core/tet_mesh.h"

namespace tissuemesh::volume::detail {

/// The Delaunay tetrahedralization of `points` (TetGen, no Steiner points), tets positively oriented.
/// Vertex indices are those of `points`.
std::vector<Tet> delaunay_tets(const std::vector<Vec3>& points);

/// `mesh` with `points` added: the constrained Delaunay mesh of its nodes plus `points` that keeps every
/// face of mesh.faces unchanged (TetGen -pYM). Old nodes keep their indices, `points` follow in order (any
/// Steiner point TetGen needs comes after them). Tissues: a tet on new point i has the tissue of
/// `source_tets[i]` (the old tet that strictly contains the point); a tet with only old nodes has that of
/// the old tet around one of its nodes in whose corner its centroid's direction lies. Tets in no old tet's
/// region (holes of `mesh`) are dropped. Faces and names are copied.
/// @pre  every points[i] lies strictly inside old tet source_tets[i]
/// @throws AlgorithmError when TetGen fails or a tet has neither an old nor a new node (Steiner points only)
TetMesh insert_constrained(const TetMesh& mesh, const std::vector<Vec3>& points,
                           const std::vector<std::uint32_t>& source_tets);

/// `mesh` without nodes no tet uses (indices renumbered in order).
void drop_unused_nodes(TetMesh& mesh);

} // namespace tissuemesh::volume::detail

// The rebuilds behind refine(): TetGen on the old nodes plus the new ones (Delaunay-only, or constrained from scratch),
// or the new nodes inserted one by one into the mesh as it is (constrained, Bowyer-Watson cavities).
#pragma once

#include <cstdint>
#include <functional>
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

/// `mesh` with `points` inserted one by one, each by a Bowyer-Watson cavity in the tissue of the old tet
/// `source_tets[i]` that holds it (the improver's insert_in_cavity(): the tets around it whose circumsphere holds the
/// point, never across a constraint face, shrunk until the point sees every face of the cavity's boundary, at most
/// 48). Every other tet stays as it is, also where the improver shaped it; no face of mesh.faces changes. A point no
/// cavity takes (on a face of the tet holding it) is left out. Old nodes keep their indices, the points taken follow
/// in order (so the result's extra nodes are their count). Faces and names are copied.
/// A point near a face of its cavity's boundary makes a flat tet with it: where a new tet is worse than 10 degrees
/// and than every tet the cavity replaces, the new node is moved to raise its tets' smallest angle (as the improver
/// smooths an inner node), and left out if that does not lift them or if it moves where `clear` (when given) says
/// no (too near an interface).
/// @pre  every points[i] lies inside old tet source_tets[i]; mesh's tets positively oriented and conforming
TetMesh insert_in_cavities(const TetMesh& mesh, const std::vector<Vec3>& points,
                           const std::vector<std::uint32_t>& source_tets,
                           const std::function<bool(const Vec3&)>& clear = {});

/// `mesh` without nodes no tet uses (indices renumbered in order).
void drop_unused_nodes(TetMesh& mesh);

} // namespace tissuemesh::volume::detail

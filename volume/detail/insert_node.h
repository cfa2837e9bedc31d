// Node insertion for the mesh improver: splits of an edge, a face or a tet at a point, and a Delaunay
// (Bowyer-Watson) cavity inside one tissue; new nodes on interfaces lie on the reference surface.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "volume/detail/surface_reference.h"
#include "volume/detail/work_mesh.h"

namespace tissuemesh::volume::detail {

/// Splits the simplex with nodes `simplex` (2, 3 or 4 of them: an edge, a face, a tet) at p: every tet
/// holding it becomes one tet per simplex node with that node replaced by the new one, and so does every
/// constraint face holding it (same tissues, same orientation; so a split on an interface keeps the interface
/// where it was, at p). Undone, and none returned, when a new tet is not positively oriented (exact).
std::optional<std::uint32_t> split_simplex(WorkMesh& mesh, const std::vector<std::uint32_t>& simplex, const Vec3& p);

/// Inserts p inside tet t's tissue by a Bowyer-Watson cavity grown from the tet holding p (found by walking
/// from t) across faces that are no constraint faces, over tets whose circumsphere holds p; the cavity is
/// shrunk until every face of its boundary sees p (exact) and its boundary is a sphere holding every node of
/// the cavity. None when no such cavity exists (p beyond a constraint face, or on a face).
std::optional<std::uint32_t> insert_in_cavity(WorkMesh& mesh, std::uint32_t t, const Vec3& p);

/// Tries nodes for tet t and keeps the best that raises the worst quality of the tets it replaces (after
/// smoothing the new node): the midpoints of t's edges and the centroids of its faces (on the reference
/// surface where they lie on constraint faces: interface splits), its centroid, and its circumcentre as a
/// Delaunay cavity. `on_interfaces` false leaves interface splits out; the faces an interface split makes
/// must hold to the reference (SurfaceReference::holds_triangle with `face_tolerance_mm`). When given, `kept`
/// judges each candidate once applied (the journal's mark before it; it rolls back what it refuses), so that a
/// refused candidate leaves the others their chance: the improver's outer-boundary and voxel rules.
/// @returns whether a node was inserted (edits of `mesh`, journaled)
bool insert_for_tet(WorkMesh& mesh, std::uint32_t t, const SurfaceReference& reference, bool on_interfaces,
                    double face_tolerance_mm, const std::function<bool(std::size_t mark)>& kept = {});

} // namespace tissuemesh::volume::detail

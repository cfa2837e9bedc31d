// Optimisation-based smoothing of one node: raise the smallest sine of the dihedral angles of its tets.
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec3.h"
#include "volume/detail/surface_reference.h"
#include "volume/detail/work_mesh.h"

namespace tissuemesh::volume::detail {

/// The point of the convex hull of `points` nearest to the origin (the zero vector when the origin lies
/// inside the hull). Exact enumeration over points, segments and triangles: for the few gradients of an
/// active set.
Vec3 min_norm_point(const std::vector<Vec3>& points);

/// Moves node v to raise the smallest dihedral-angle sine over its tets: steepest ascent of that
/// non-smooth minimum (Freitag, Jones and Plassmann's active-set method, as in Stellar): the direction is the
/// smallest vector in the hull of the gradients of the sines within reach of the minimum, the step is where
/// the linear model meets the next sine, halved until the minimum really rises. Interior nodes move freely;
/// surface nodes along their patch and curve nodes along their junction curve of `reference`, projected back
/// onto it after every step; corners stay. A step is taken only when every tet of v stays positively
/// oriented (exact predicate), no constraint face at v turns over, every constraint face at v stays on the
/// reference (SurfaceReference::holds_triangle within `face_tolerance_mm`), and the minimum rises.
/// @returns whether v moved (the moves are edits of `mesh`, journaled like any other)
bool smooth_node(WorkMesh& mesh, std::uint32_t v, const SurfaceReference& reference, double face_tolerance_mm,
                 int max_steps = 8);

} // namespace tissuemesh::volume::detail

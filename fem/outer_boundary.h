// The outer boundary of a tet mesh: faces that belong to exactly one tet.
#pragma once

#include <cstdint>
#include <vector>

#include "core/tet_mesh.h"

namespace tissuemesh::fem {

/// Outer boundary of `mesh`, found from the tets alone (the mesh's face list is not needed).
struct OuterBoundary {
    std::vector<Triangle> faces;      ///< #B faces of exactly one tet, oriented outwards, sorted
    std::vector<std::uint32_t> nodes; ///< sorted vertex indices of those faces
};

/// Faces shared by no other tet (the insulated outer surface and any inner cavity's surface).
/// @throws InputError when a vertex index is out of range or a coordinate is not finite
OuterBoundary outer_boundary(const TetMesh& mesh);

/// The part of outer_boundary() near a ball: its faces with at least one node within `radius_mm` of
/// `centre_mm`, and its nodes within that distance; the faces are paired only among the tets around those
/// nodes (an electrode's patch without pairing the faces of the whole mesh). Equal to the cut whole
/// boundary on conforming meshes (no face in more than two tets; tm-check-mesh counts such faces).
/// @throws InputError when a vertex index is out of range, or the centre or radius is not finite
OuterBoundary outer_boundary_near(const TetMesh& mesh, const Vec3& centre_mm, double radius_mm);

} // namespace tissuemesh::fem

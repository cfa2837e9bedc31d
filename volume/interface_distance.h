// How far a tet mesh's interfaces lie from the interface complex it was made from.
#pragma once

#include <cstddef>

#include "core/interface_complex.h"
#include "core/tet_mesh.h"

namespace tissuemesh::volume {

/// Distances in mm from the mesh's interface and boundary faces to the complex, each measured to the
/// complex's triangles of the same tissue pair (either orientation).
struct InterfaceDistance {
    std::size_t nodes = 0;  ///< nodes on the mesh's faces
    double max_node_mm = 0; ///< largest distance of such a node (a node on several patches: the largest)
    double mean_node_mm = 0;
    std::size_t faces = 0;
    double max_face_mm = 0;          ///< largest distance of a face's centroid or edge midpoint
    double mean_face_mm = 0;         ///< area-weighted mean over the faces of their centroids' distances
    std::size_t unmatched_faces = 0; ///< faces whose tissue pair the complex does not have (not in the figures)
};

/// Measures `mesh`'s faces against `surface`. Linear in the faces (a spatial index over the complex).
/// @throws InputError when the mesh has no faces
InterfaceDistance interface_distance(const TetMesh& mesh, const InterfaceComplex& surface);

} // namespace tissuemesh::volume

// 3-D rasterization of a tet mesh over a voxel grid: which tet holds each voxel centre.
#pragma once

#include <cstdint>
#include <vector>

#include "core/label_image.h"
#include "core/progress.h"
#include "core/tet_adjacency.h"
#include "core/tet_mesh.h"

namespace tissuemesh::volume {

/// For every voxel of `image` (linear index as LabelImage::linear_index), the index of the tet whose
/// closed region contains the voxel centre, or -1 when the centre lies outside the mesh.
///
/// Tie-breaking: a centre on a face, edge or vertex shared by several tets is given to exactly one of
/// them, as if it were moved by an infinitesimal step along (1, e, e^2) in voxel-index space (e -> 0):
/// on a face plane, the side the face's normal points to when its first non-zero component (x, then y,
/// then z) is positive. Each face's test is evaluated once per face in a canonical vertex order, so two
/// tets sharing a face can never both claim (or both refuse) a centre on it. The rule is exact only as far as
/// the plane tests are: a centre on an edge or a node of the mesh may be refused by every tet around it when they
/// round differently, so a centre no tet claims goes to the first tet it lies within 1e-9 voxel of. Orientation and
/// spacing of the image are honoured (tests run in continuous index coordinates). Cost: linear in voxels covered by the
/// tets' bounding boxes plus tets.
/// @pre  mesh tets are positively oriented (TetMesh's invariant) and the mesh is conforming
std::vector<std::int32_t> rasterize_tets(const TetMesh& mesh, const LabelImage& image, const Progress& progress = {});
/// The same with the mesh's face adjacency built before (it tells the outer boundary's faces).
std::vector<std::int32_t> rasterize_tets(const TetMesh& mesh, const LabelImage& image, const TetAdjacency& adjacency,
                                         const Progress& progress = {});

} // namespace tissuemesh::volume

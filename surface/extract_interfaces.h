// Tissue interfaces from a label image: multi-material marching cubes on the Freudenthal (Kuhn)
// tetrahedralization of the voxel-centre grid, with the barycentric-dual surface in each tetrahedron.
#pragma once

#include <vector>

#include "core/interface_complex.h"
#include "core/label_image.h"
#include "core/progress.h"

namespace tissuemesh::surface {

/// Options for extract_interfaces().
struct ExtractOptions {
    /// Tissues to keep (empty: every label in the image). Any other label is merged into `background`.
    std::vector<Label> tissues;
    /// The label standing for "no tissue"; the image is padded with one voxel layer of it, so the outside
    /// of the image counts as background and every surface is closed.
    Label background = 0;
};

/// Builds the interface complex of `image`.
///
/// Method (why: it guarantees the invariants by construction, with no case tables to get wrong):
///  - the cube grid whose corners are voxel centres (padded by one background voxel all round) is split
///    into tetrahedra by the Kuhn/Freudenthal decomposition: cube corner 0 to corner (1,1,1), 6 tetrahedra
///    per cube, the same in every cube, so the whole grid is one conforming tetrahedralization;
///  - in each tetrahedron the corner labels are separated by the barycentric-dual surface: vertices at
///    edge midpoints, at face centroids (faces with 3 labels) and at the tetrahedron centroid (3-4 labels);
///    a tetrahedron with 2 labels gives the marching-tetrahedra triangle or planar quad (split along the
///    diagonal from the midpoint of the edge between the lowest corners of each side);
///  - a face's curve depends only on its own corner labels, so neighbouring tetrahedra share it exactly.
///
/// Post-conditions (tested in tests/surface):
///  - every tissue's region (including background) is bounded by a closed, consistently oriented
///    2-manifold; triangles do not intersect except along shared edges and vertices; no triangle is
///    degenerate; junction curves are shared exactly (vertices are keyed by grid edge/face/tetrahedron,
///    never welded by position);
///  - connectivity rule: two voxels of the same tissue are connected when they are one of the 14
///    Freudenthal neighbours: the 6 face neighbours, (+-1,+-1,0)-type neighbours along the increasing
///    face diagonals only ((1,1,0), (1,0,1), (0,1,1) and their negatives), and (1,1,1), (-1,-1,-1).
///    The same rule holds for the complement, so each connected component of a tissue has its own
///    surface, and components never touch each other: a tissue's surface has c(tissue) + c(rest) - 1
///    edge-connected pieces, c counting 14-connected components in the padded image (a shell: 1 + 2 - 1);
///  - sides: `from` is the tissue with the larger label and `to` the smaller one, except that the
///    background is always `to` (normals of a tissue against background point outward);
///  - vertices are in world mm (image.index_to_world); with a direction matrix of negative determinant
///    the vertex order is flipped so normals still point from `from` into `to`;
///  - vertex positions are the dual points' index positions (midpoints: labels carry no sub-voxel
///    information); smoothing is a later step.
/// There are no ambiguous configurations to resolve: the fixed diagonal of the decomposition decides
/// them, as the connectivity rule states. (A per-tissue priority would have to choose diagonals per cube
/// face and re-triangulate cubes; not offered.)
/// Works slab by slab (two voxel layers at a time); memory beyond the output is O(nx * ny).
/// @throws InputError when the image is empty, `background` is among `tissues`, a chosen tissue is absent
///         from the image, or nothing but background remains
InterfaceComplex extract_interfaces(const LabelImage& image, const ExtractOptions& options = {},
                                    const Progress& progress = {});

} // namespace tissuemesh::surface

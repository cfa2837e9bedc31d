// Tissue interfaces from a label image: multi-material marching cubes on the Freudenthal (Kuhn)
// tetrahedralization of the voxel-centre grid, with the barycentric-dual surface in each tetrahedron.
#pragma once

#include <map>
#include <vector>

#include "core/interface_complex.h"
#include "core/interface_sink.h"
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
    /// Thin-tissue priority per label (higher wins; unlisted labels rank below every listed one; empty:
    /// the plain Kuhn rule, output identical to having no such option). See "Priority rule" below.
    std::map<Label, int> priority;
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
/// Without a priority there are no ambiguous configurations to resolve: the fixed diagonal of the
/// decomposition decides them, as the connectivity rule states.
///
/// Priority rule (ExtractOptions::priority non-empty), for tissues one voxel thick that touch themselves
/// only through cube edges/corners (a one-voxel shell, a CSF layer):
///  - face diagonal: a cube face (4 corners) uses its non-Kuhn diagonal exactly when that diagonal joins
///    two corners of a listed tissue T and both other corners are not T and rank below T ("checkerboard
///    for T"); otherwise the Kuhn diagonal. It depends on the face's labels only, so both cubes sharing
///    the face agree;
///  - cube: let T be the cube's top label (highest rank; ties: the most frequent, then the smallest
///    label). The cube is split into 12 tetrahedra (each face's two triangles coned to the cube centre,
///    a lattice point labelled T) when T is listed and a face uses its non-Kuhn diagonal, or T's corners
///    are not connected by the cube's Kuhn edges, or corners 0 and (1,1,1) are both not T and every path
///    of cube edges between them meets T (the Kuhn main diagonal would cross T); otherwise it keeps its 6
///    Kuhn tetrahedra;
///  - the dual surface is built on these tetrahedra exactly as above (new points keyed by the exact
///    barycentre of their simplex, which names it, so sharing stays exact; points lie on the 1/24-voxel
///    lattice instead of 1/12);
///  - connectivity rule: two lattice points (voxel centres and centres of split cubes) of the same tissue
///    are connected when an edge of this tetrahedralization joins them: the 6 face neighbours, each
///    face's chosen diagonal, the Kuhn main diagonal of unsplit cubes, and centre-to-corner edges of split
///    cubes. So wherever a listed tissue is a cube's top label, any two of its corners in that cube are
///    connected (26-style; split or not), and the 14-neighbourhood holds everywhere else; in a split
///    cube the other labels are connected only along cube edges and chosen face diagonals. The surface of a tissue has
///    c(tissue) + c(rest) - 1 pieces with c counted under this rule (rest: every other label, split-cube centres
///    included).
/// Works slab by slab (two voxel layers at a time); memory beyond the output is O(nx * ny) (with a
/// priority, plus a hash map of the current slab's split-cube points).
/// @throws InputError when the image is empty, `background` is among `tissues`, a chosen tissue is absent
///         from the image, nothing but background remains, a priority names a label that is neither a
///         kept tissue nor the background, or (with a priority) an image side exceeds 80 000 voxels
InterfaceComplex extract_interfaces(const LabelImage& image, const ExtractOptions& options = {},
                                    const Progress& progress = {});

/// The same complex handed to `sink` slab by slab instead of returned, so that a writer never holds it
/// whole (tm-extract streams the head's 6.5 M triangles to a PLY file this way). The pieces are the
/// slabs in z order (image.dims()[2] + 1 of them, some empty); their concatenation is exactly the complex
/// the overload above returns (same vertices, triangles and order). Locality, which streaming consumers
/// may rely on: a triangle of piece k uses only vertices of pieces k - 1 and k, hence all the triangles
/// around an edge arrive within two consecutive pieces. The options are checked before the first piece;
/// an exception thrown later (over 2^32 - 1 vertices, an AlgorithmError) leaves `sink` with a partial
/// complex, to be discarded.
/// @throws as the overload above
void extract_interfaces(const LabelImage& image, const ExtractOptions& options, InterfaceSink& sink,
                        const Progress& progress = {});

} // namespace tissuemesh::surface

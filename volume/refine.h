// Adaptive refinement (Mueller & Sachse): new nodes in the worst-assessed tets until the mesh matches the voxels.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/label_image.h"
#include "core/progress.h"
#include "core/tet_mesh.h"
#include "volume/assess.h"
#include "volume/improve_mesh.h"

namespace tissuemesh::volume {

/// Where a new node goes in a selected tet.
enum class Placement {
    centroid,            ///< the tet's centroid
    incentre,            ///< the centre of its inscribed sphere
    longest_edge,        ///< the midpoint of its longest edge
    material_half_edges, ///< first tissue change walking from each edge midpoint towards both vertices
    material_centroid,   ///< first tissue change walking from the centroid towards each vertex
};

/// Options for refine(). Lengths in mm, volumes in mm^3.
struct RefineOptions {
    Placement placement = Placement::material_centroid;
    double batch_fraction = 0.05;       ///< share of the tets refined per round, worst quality keys first
    std::size_t min_batch = 16;         ///< at least this many tets per round (when that many qualify)
    double target_error_mm3 = 0;        ///< stop when the total error volume is at or below this (0: unused)
    double target_error_percent = 0;    ///< ... or below this % of the mesh volume (0: unused)
    std::size_t max_nodes = 0;          ///< node budget (0: none); the last batch is cut to fit it
    std::size_t max_iterations = 50;    ///< rounds at most
    std::size_t max_stalled_rounds = 3; ///< Delaunay-only: stop when the error volume has not fallen over this
                                        ///< many rounds (0: never)
    double initial_spacing_mm = 0;      ///< Delaunay-only: lattice spacing of the start mesh (0: box size / 4)
    double min_node_distance_mm = 0;    ///< no new node closer than this to another node, nor (constrained)
                                        ///< to an interface face (0: half the smallest voxel spacing)
    AssessOptions assess;               ///< priority weights and quality key weights
    bool improve = true;                ///< improve the final mesh's tets (improve_mesh(), its own interfaces as the
                                        ///< reference): the cavities of new nodes leave tets under the target
    /// Its options: by default tm-tetra's (flips, moves, interface nodes sliding on their interfaces, new nodes),
    /// so the refined mesh is no worse shaped than the one tm-tetra made. Interface moves and new nodes change
    /// what the tets cover a little: the error volume is then measured again (RefineReport). With a node budget
    /// the improver adds no node; Delaunay-only, it flips and moves inner nodes only.
    ImproveOptions improvement{};
    /// Constrained: each round rebuilds the whole mesh with TetGen from its nodes and faces (the refinement before
    /// 2026-12-08), instead of inserting the new nodes one by one into the mesh as it is (Bowyer-Watson cavities,
    /// the rest of the tets kept).
    bool tetgen_rebuild = false;
};

/// One round: the mesh after it (iteration 0 is the start mesh).
struct RefineIteration {
    std::size_t iteration = 0;
    std::size_t nodes = 0;
    std::size_t tets = 0;
    std::size_t added_nodes = 0;       ///< nodes placed in this round
    std::size_t reassessed_tets = 0;   ///< tets that were new and so assessed in this round
    double total_error_volume_mm3 = 0; ///< voxel centres not of their tet's tissue x voxel volume
    double worst_quality_key = 0;      ///< largest quality key (larger = worse)
    double seconds = 0;                ///< since refine() started
};

/// What refine() did.
struct RefineReport {
    std::vector<RefineIteration> iterations;
    std::string stop_reason;     ///< "target reached", "node budget", "iteration cap", "stalled",
                                 ///< "no error left", "no node could be placed", or a round undone: "the
                                 ///< next round's rebuild was not fit for FEM (undone)", "... failed (TetGen)"
    bool target_reached = false; ///< a target was given and met
    double mesh_volume_mm3 = 0;
    bool improved = false; ///< improve_mesh() ran on the result; `improvement` says what it did
    ImproveReport improvement;
    double improved_error_volume_mm3 = -1; ///< the error volume of the improved mesh when the improver could change
                                           ///< it (interface moves, new nodes); -1: not measured (unchanged)
};

/// Refines a tet mesh against `image` by the paper's loop: assess every tet, place one node in each of the
/// worst ones (a batch per round, ordered by quality key), put the nodes into the mesh, and assess only the tets
/// that are new (unchanged tets keep their assessment, which is exactly what a full assessment would give them: the
/// rasterization's tie rule depends on each face alone).
///
/// Two modes:
///  - Delaunay-only (`constrained == nullptr`): the start mesh is the Delaunay mesh of a lattice over the
///    image's world bounding box (corners included); every tet takes its majority tissue, so the mesh fills
///    the box and background tets carry options.assess.background. Only tets with a positive error volume
///    are refined; the result's interface faces are rebuilt from the labels (mark_interfaces).
///  - constrained (`constrained` is a mesh from tetrahedralize()): its interface and boundary faces are kept
///    exactly, new nodes go strictly inside tets, and a new tet takes the tissue of the region it lies in, so
///    labels never cross an interface and the total error volume stays what the interfaces give (nodes improve
///    shape and resolution, not the voxel match). The worst keys of all tets are refined. Each node goes into the
///    mesh as it is, by a Bowyer-Watson cavity inside its tissue (detail::insert_in_cavities(): the paper's
///    successive Delaunay insertion; the other tets, as the improver shaped them, stay), or, with
///    RefineOptions::tetgen_rebuild, the whole mesh is made again by TetGen (-pY) from its nodes and faces.
/// Material-change placement samples the image (nearest voxel, outside: background) along the rays in
/// world mm every quarter voxel, bisects the first change to 1/64 voxel, and of the changes found takes the
/// one farthest from the tet's vertices; with none it falls back to the centroid. A node closer than
/// min_node_distance_mm to another (constrained mode: or to an interface or boundary face) is dropped; when
/// fewer than a tenth of a batch's nodes remain, the batch
/// is placed again with the tets' centroids in place of the dropped nodes (dropped again when too close).
/// A valid mesh is always returned: the last complete round's, improved (options.improve) by improve_mesh()
/// against its own interface faces (interface nodes slide on them; see RefineOptions::improvement); the minimum
/// distance of new nodes to the interfaces is a rule of placement, which the improver's moves do not keep.
/// @pre  image not empty; `constrained` (when given) passes check_mesh()
/// @throws InputError when an option is out of range or the image is empty
/// @throws AlgorithmError when TetGen fails (Delaunay-only, or RefineOptions::tetgen_rebuild)
TetMesh refine(const LabelImage& image, const TetMesh* constrained, const RefineOptions& options = {},
               const Progress& progress = {}, RefineReport* report = nullptr);

/// The placement's name as tm-refine spells it ("material-half-edges"), and back.
std::string placement_name(Placement placement);
/// @throws InputError for an unknown name, listing the known ones
Placement parse_placement(const std::string& name);

} // namespace tissuemesh::volume

// Tet mesh improvement that keeps tissues and interfaces: worst tets first, by smoothing, flips and node
// insertion (after Klingner and Shewchuk's Stellar, "Aggressive tetrahedral mesh improvement", IMR 2007),
// extended to interior interfaces.
#pragma once

#include <cstddef>
#include <map>

#include "core/interface_complex.h"
#include "core/label_image.h"
#include "core/progress.h"
#include "core/tet_mesh.h"

namespace tissuemesh::volume {

/// Options for improve_mesh(). Angles in degrees.
struct ImproveOptions {
    /// Tets whose smallest dihedral angle (or 180 minus the largest) is below this are worked on, worst first.
    /// 21 rather than 22 (measured on the default workflow's tm-tetra meshes, improver CPU seconds, smallest
    /// angle, 1st percentile): usc19-5 at 1 mm 22.5 -> 18.0 s, 11.36 both, 22.21 -> 21.37; torso 25.9 -> 18.1 s,
    /// 9.28 both, 22.25 -> 21.35; liver 18.37 -> 20.06, 22.37 -> 21.44. 20 leaves the 1st percentile at 20.5.
    double target_dihedral_deg = 21;
    std::size_t max_passes = 5; ///< rounds over the tets below the target (fewer when one changes nothing)
    bool smooth = true;         ///< move nodes (interior nodes anywhere; see move_interface_nodes)
    bool flip = true;           ///< edge removal (3-2, 4-4, ... flips) and multi-face removal (2-3 flips)
    bool insert = true;         ///< new nodes inside tissues (splits and Delaunay cavities)
    /// Insertion only for tets whose smallest dihedral angle is below this: it costs a dozen trials a tet, and
    /// smoothing and flips mend most tets. 20 rather than 15 (measured after tm-tetra, 1st percentile, tets under
    /// 20 degrees, improver seconds): sphere head at 2 mm 19.86 -> 20.83, 3 742 -> 217, 11.2 -> 9.6 s; usc19-5
    /// at 1 mm 21.96 -> 22.18, 4 590 -> 502, 14.3 -> 17.7 s.
    double insert_below_deg = 20;
    bool move_interface_nodes = true; ///< interface nodes slide on their interface, junction nodes along their
                                      ///< junction curve (of the reference surface), corners never move; and
                                      ///< interface edges flip where the four nodes lie (nearly) in the surface
    bool insert_on_interfaces = true; ///< new nodes on interfaces (splitting interface triangles, at points of
                                      ///< the reference surface)
    /// An interface face a move, flip or split makes stays this close to the reference surface (centroid and
    /// edge midpoints), as a fraction of the reference's mean edge length: nodes slide freely on flat
    /// interfaces, on curved or creased ones only as far as their faces follow. 0.03 of the 1 mm usc19-5 head's
    /// 2.4 mm edges is 0.07 mm, under a tenth of its voxel. Measured on that head (same surfaces), smallest
    /// dihedral angle and tets under 10 degrees after tm-tetra, then tm-refine: 0.01: 3.37 deg, 307; 4.57, 51.
    /// 0.02: 3.86, 95; 5.27, 20. 0.03: 3.69, 56; 6.66, 20. 0.04: 2.11, 72; 6.69, 13, but on the liver sample
    /// TetGen then crashed rebuilding the improved mesh in tm-refine (it did not with 0.01-0.03).
    /// In the last round, a tet left under 0.95 of the target (detail::rescue_fraction) that no edit lifts gets its
    /// edits again with faces allowed 2, then 4 times as far (improver.cpp; the 0.7 mm head's 8.92-degree sliver
    /// between two junction curves).
    double max_face_deviation = 0.03;
    /// Each tissue's volume stays within this fraction of its start (moves and splits on curved interfaces that would
    /// take it further are refused); in parts, of its volume in the part, and in the last round after the parts, of
    /// the whole mesh's (so at most three times this in all).
    double max_volume_change = 2e-4;
    /// No edit leaves a tet it made or reshaped larger than this (mm^3; 0: no bound), nor one of a tissue in
    /// the map larger than the tissue's bound: tm-tetra's --max-volume bounds, which node moves would otherwise
    /// break (measured: tets of 0.65 mm^3 under a bound of 0.5 with the 22-degree target).
    double max_tet_volume_mm3 = 0;
    std::map<Label, double> max_tet_volume_per_tissue_mm3;
    /// The mesh is cut into this many parts across its longest side, improved side by side (the nodes on the
    /// faces between parts held still), then bands around those faces (and around any tet left under half the
    /// target) are improved the same way. 0: one part per 200 000 tets rounded down to an even number, at least
    /// two from 20 000 tets on and at most 8 (one under 20 000); 1: the whole mesh at once. The result depends on
    /// this, not on the thread count.
    std::size_t parts = 0;
    /// The voxels the interfaces were made from (world coordinates, as the mesh), or null. When given, an edit that
    /// moves, flips or splits interface faces (junction-curve nodes included) is undone when the region they sweep
    /// holds the centre of a voxel next to another label (the rule of tm-remesh --keep-voxel-sides), and the tet's
    /// next edit tried: the Dice against these voxels stays that of the input mesh, the smallest angles a little
    /// lower (docs/volume.md). A last pass over the tets still under half the target does not ask the voxels.
    /// The image must outlive the call.
    /// @throws InputError (from improve_mesh()) when the mesh reaches two voxels beyond the image's box
    const LabelImage* voxel_image = nullptr;
};

/// Shape figures of a mesh. A tet's smallest dihedral angle is its quality here.
struct ShapeFigures {
    double min_dihedral_deg = 0;       ///< smallest dihedral angle of any tet
    double max_dihedral_deg = 0;       ///< largest dihedral angle of any tet
    double p1_min_dihedral_deg = 0;    ///< 1st percentile of the tets' smallest dihedral angles
    std::size_t tets_under_10_deg = 0; ///< tets with a dihedral angle below 10 degrees
    std::size_t tets_under_20_deg = 0;
    std::size_t tets = 0;
};

/// The figures of `mesh` (one pass over its tets).
ShapeFigures shape_figures(const TetMesh& mesh);

/// What improve_mesh() did.
struct ImproveReport {
    ShapeFigures before, after;
    std::size_t smoothed_nodes = 0;          ///< node moves kept
    std::size_t edges_removed = 0;           ///< edge removals (3-2 and 4-4 flips among them)
    std::size_t faces_removed = 0;           ///< multi-face removals (2-3 flips among them)
    std::size_t interface_edges_flipped = 0; ///< 2-2 flips of interface triangles (their tets remade on both sides)
    std::size_t nodes_inserted = 0;          ///< inside tissues
    std::size_t nodes_inserted_on_interfaces = 0;
    std::size_t refused_by_voxels = 0; ///< edits refused for carrying a voxel centre across (voxel_image)
    /// Edits refused because a face of the outer boundary they made or moved met another (detail/outer_boundary.h).
    std::size_t refused_crossing_boundary = 0;
    std::size_t passes = 0;
    std::size_t parts = 1; ///< parts improved side by side (ImproveOptions::parts)
    std::size_t bands = 0; ///< then bands around the faces between them
    double seconds = 0;
    double cpu_seconds = 0; ///< processor time of the calling process meanwhile
};

/// Improves the shape of `mesh`'s tets where they are below the target, worst first: smoothing that maximises
/// the smallest sine of the dihedral angles around a node, edge and multi-face removal, and node insertion
/// (in tissues, and on interfaces at points of the reference surface). The reference is `surface` (the
/// complex the mesh was made from) or, in the overload without it, the mesh's own interface and boundary faces
/// as they are on entry. Every step raises the worst quality of the tets it replaces, so the worst tet of the
/// mesh never gets worse; every tet stays positively oriented (exact predicates); no tet changes tissue; no
/// interface or boundary face is removed other than by splitting it at a point of the reference surface, and
/// interface nodes stay on it. Runs its parts (ImproveOptions::parts) on every core; deterministic.
/// @pre  `mesh` is conforming with positively oriented tets (check_mesh() finds no inverted tet, no
///       non-conforming face); its faces are its interface and outer-boundary faces
/// @post the same, and the interfaces are those of the reference surface
/// @throws InputError when the mesh is not conforming or an option is out of range
ImproveReport improve_mesh(TetMesh& mesh, const InterfaceComplex& surface, const ImproveOptions& options = {},
                           const Progress& progress = {});
ImproveReport improve_mesh(TetMesh& mesh, const ImproveOptions& options = {}, const Progress& progress = {});

} // namespace tissuemesh::volume

// Isotropic remeshing of an interface complex: well-shaped triangles of a target size on the same surfaces,
// junction curves remeshed as curves, never an invalid complex.
#pragma once

#include <cstddef>
#include <map>
#include <utility>

#include "core/interface_complex.h"
#include "core/progress.h"

namespace tissuemesh::surface {

/// Options of remesh(). Lengths in mm, angles in degrees.
struct RemeshOptions {
    double target_edge_mm = 0; ///< target edge length (required unless every patch has one by pair)
    /// Target edge length per tissue pair (either order), overriding target_edge_mm on that patch; an edge
    /// takes the smallest target of the patches around it.
    std::map<std::pair<Label, Label>, double> target_edge_mm_by_pair;
    std::size_t iterations = 3; ///< split / collapse / flip / relax rounds (docs/surfaces.md: why 3)
    /// Relaxation leaves a vertex where it is when its relaxed place is closer than this fraction of its target edge:
    /// so short a move barely changes its triangles, and judging it costs as much as any other (docs/surfaces.md,
    /// "Fewer idle moves again": 0.05 since the twentieth session, 0.02 before).
    double min_relax_move = 0.05;
    double min_angle_deg = 15;         ///< no edit may create an angle below this (unless not worse)
    double max_normal_change_deg = 30; ///< one edit may tilt a triangle at most this much
    double min_gap_mm = 0.1;           ///< distance kept between patches (unless closer before)
    /// Smallest angle kept between neighbouring triangles around an edge that holds a tissue (unless an edit
    /// leaves it no smaller than before): it bounds the dihedral angles of the tets there (0: no rule).
    double min_sector_deg = 15;
    /// Edges no longer than this many times the thickness of the tissue layer they bound, measured on the
    /// input along its normals, and growing by at most half their distance from thin places (0: no such
    /// limit). A layer thinner than its edges is filled with flat tets (surface/detail/layer_sizing.h).
    double edge_per_thickness = 0;
    double min_edge_mm = 0; ///< with edge_per_thickness: no target below this (0: a third of target_edge_mm)
    /// The label image the complex was extracted from (not owned; nullptr: none). With it, no move or collapse of a
    /// patch vertex carries the centre of a voxel next to another label across the surface
    /// (surface/detail/voxel_sides.h): the surfaces keep the voxels' tissues where the image has them.
    const LabelImage* voxel_image = nullptr;
    /// Slabs remeshed side by side (in parallel), then bands around the cuts between them; 0: one per
    /// 125 000 triangles, at most 8. The result depends on it, never on the thread count. At most max_slabs.
    std::size_t slabs = 0;
    static constexpr std::size_t max_slabs = 64; ///< each slab costs a pass over the whole complex
};

/// What remesh() did.
struct RemeshReport {
    std::size_t triangles_before = 0;
    std::size_t triangles_after = 0;
    std::size_t splits = 0;
    std::size_t collapses = 0;
    std::size_t flips = 0;
    std::size_t moves = 0;
    std::size_t refused = 0;           ///< edits the validity checks (or the slabs' fences) refused
    std::size_t refused_by_voxels = 0; ///< moves and collapses that would carry a voxel centre across (voxel_image)
    std::size_t slabs = 1;             ///< slabs remeshed side by side (RemeshOptions::slabs)
    double min_angle_before_deg = 0;   ///< smallest triangle angle
    double min_angle_after_deg = 0;
    /// Smallest angle between neighbouring triangles around an edge that holds a tissue (edge_fan.h's
    /// smallest_sector_deg()): it bounds the dihedral angles of any tet mesh keeping the complex.
    double min_sector_before_deg = 0;
    double min_sector_after_deg = 0;
    double mean_edge_after_mm = 0;
    double max_distance_mm = 0;     ///< largest distance of a final vertex to the input surface
    std::size_t thin_triangles = 0; ///< input triangles on layers thinner than edge_per_thickness allows
};

/// Remeshes `complex` in place towards edges of the target length (Botsch and Kobbelt 2004): split edges
/// longer than 4/3 of it, collapse edges shorter than 4/5 of it, flip edges towards valence 6, and move
/// vertices to the mean of their neighbours within the tangent plane, then back onto the input surface
/// (patch vertices onto the input patch of the same tissue pair, junction vertices onto the input junction
/// curves). Junction edges are split and collapsed along their curve; corners stay. Every edit goes
/// through the validity checks of surface/detail/complex_editor.h, so a valid input stays valid.
/// @pre  `complex` passes check_complex()      @post it still does, with the same topology per tissue
/// @throws InputError when no target length is given or options are out of range
RemeshReport remesh(InterfaceComplex& complex, const RemeshOptions& options, const Progress& progress = {});

} // namespace tissuemesh::surface

// Decimation of an interface complex by edge collapses: few triangles where the surface is flat, many
// where it curves (or sizes from a size field), never an invalid complex.
#pragma once

#include <cstddef>
#include <map>
#include <utility>

#include "core/interface_complex.h"
#include "core/progress.h"

namespace tissuemesh::surface {

/// What decides which edges go first.
enum class DecimateMode {
    curvature, ///< quadric error (Garland-Heckbert): flat places coarsen first, curved places stay fine
    size,      ///< edge length against a target size per tissue pair: short edges collapse, long ones split
};

/// Options of decimate(). Lengths in mm, angles in degrees.
struct DecimateOptions {
    DecimateMode mode = DecimateMode::curvature;
    std::size_t target_triangles = 0; ///< stop at or below this count (0: only the limits stop it)
    /// No vertex of the input may end up further than this from the output surface (a one-sided
    /// Hausdorff bound, tracked through every collapse).
    double max_distance_mm = 0.5;
    /// Curvature mode only (size mode refuses it): no collapse may leave an edge longer than this (0: no
    /// bound). Before remeshing to a target edge L, 4/3 L spares the remeshing from splitting the long
    /// edges of flat places (which it would then collapse again) and the decimation from the collapses
    /// that make them.
    double max_edge_mm = 0;
    /// Curvature mode with max_edge_mm: nor longer than 4/3 of this many times the thickness of the tissue layer
    /// the edge bounds, measured on the input along its normals (tm-remesh's sizing with a target of 3/4
    /// max_edge_mm: surface/detail/layer_sizing.h). Collapses over a thin layer otherwise leave triangles as
    /// long as max_edge_mm there, which the remeshing splits back only where its checks allow (0: no such bound).
    double edge_per_thickness = 0;
    double max_normal_change_deg = 20; ///< a collapse may tilt a triangle at most this much
    double min_angle_deg = 5;          ///< no collapse may create an angle below this (unless not worse)
    double min_gap_mm = 0.1;           ///< triangles sharing no vertex keep this distance (unless closer before)
    /// Smallest angle kept between neighbouring triangles around an edge that holds a tissue (unless a
    /// collapse leaves it no smaller than before): it bounds the dihedral angles of the tets there (0: no rule).
    double min_sector_deg = 15;
    /// Size mode: target edge length (0: none). Edges shorter than 4/5 of it collapse, longer than 4/3 split.
    double target_edge_mm = 0;
    /// Size mode: target edge length per tissue pair (either order), overriding target_edge_mm.
    std::map<std::pair<Label, Label>, double> target_edge_mm_by_pair;
    /// Curvature mode: before the collapses, the patch vertices in each cube of this edge (one grid over the whole
    /// complex) that are joined by edges are contracted into one of them, the first in the order of their summed
    /// quadrics' error that every check of a collapse, the edge bound and half the distance bound allow (0: off). One
    /// judgement for a few vertices, but not measurably faster at equal fidelity (docs/surfaces.md).
    double contract_block_mm = 0;
    /// Slabs decimated side by side (in parallel); then, from the seams their fences held back, slabs cut
    /// halfway between them, side by side again; then one pass over the whole from what is left; 0: one per
    /// 400 000 triangles, at least 2 from 50 000 triangles on, at most 8. The result depends on it, never on the thread
    /// count. With target_triangles (a global count) there is one slab. At most max_slabs.
    std::size_t slabs = 0;
    static constexpr std::size_t max_slabs = 64; ///< each slab costs a pass over the whole complex
};

/// What decimate() did.
struct DecimateReport {
    std::size_t triangles_before = 0;
    std::size_t triangles_after = 0;
    std::size_t collapses = 0;
    std::size_t splits = 0;
    std::size_t contractions = 0;         ///< clusters contracted (DecimateOptions::contract_block_mm)
    std::size_t contracted_vertices = 0;  ///< vertices they removed
    std::size_t contractions_refused = 0; ///< clusters left to the collapses (why: in the refused_* counts below but
                                          ///< refused_by_distance, refused_by_length and refused_by_checks)
    std::size_t slabs = 1;                ///< slabs decimated side by side (DecimateOptions::slabs)
    std::size_t refused_by_distance = 0;  ///< collapses that would leave an input vertex too far
    std::size_t refused_by_length = 0;    ///< collapses that would leave an edge longer than max_edge_mm
    std::size_t refused_by_checks = 0;    ///< collapses refused as invalid (the five below)
    std::size_t refused_topology = 0;     ///< link condition, junction rules
    std::size_t refused_shape = 0;        ///< small angle or degenerate
    std::size_t refused_fold = 0;         ///< a triangle would tilt too much
    std::size_t refused_intersection = 0; ///< a triangle would meet another
    std::size_t refused_gap = 0;          ///< a triangle would come too close to another patch
    std::size_t refused_wedge = 0;        ///< two triangles sharing one vertex would nearly lie on each other
    double max_distance_mm = 0;           ///< largest tracked distance of an input vertex to the output
};

/// Simplifies `complex` in place by half-edge collapses (a vertex merges into a neighbour, which keeps
/// its place), cheapest first. Junction curves are features: a vertex on one collapses only along it;
/// curve corners stay. Every collapse must pass the editor's validity checks (link condition, no fold,
/// no intersection, no gap closing: surface/detail/complex_editor.h) and the distance bound, so the
/// result passes check_complex() whenever the input does.
/// @pre  `complex` passes check_complex()      @post it still does, with the same topology per tissue
/// @throws InputError when options are out of range
DecimateReport decimate(InterfaceComplex& complex, const DecimateOptions& options = {}, const Progress& progress = {});

} // namespace tissuemesh::surface

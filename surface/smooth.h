// Smoothing of an interface complex, held to the voxel evidence: terraces of marching cubes become
// smooth surfaces without leaving what the label image allows.
#pragma once

#include <cstddef>

#include "core/interface_complex.h"
#include "core/label_image.h"
#include "core/progress.h"

namespace tissuemesh::surface {

/// Options of smooth(). Angles in degrees.
struct SmoothOptions {
    std::size_t iterations = 10; ///< Taubin lambda|mu step pairs
    /// Pairs run between two checks against the complex (0: all of them, checked once). Each pair is held
    /// to the image and to the rules of a single triangle (shape, tilt) on its own; the costly rules between
    /// triangles (intersection, gap, wedge) judge the net move of the run. On the 1 mm usc19-5 head, smoothing
    /// step / triangles after tm-decimate 0.5 mm: 1 per check 197 s / 557 198; 5 per check 50 s / 555 810;
    /// all 10 at once 36 s / 587 183 (a move refused at the end loses the whole run; spheres4 at 1 mm gives
    /// the same bytes in all three).
    std::size_t pairs_per_check = 5;
    double lambda = 0.6307; ///< shrinking step factor (Taubin 1995: pass band k_PB = 0.1)
    double mu = -0.6732;    ///< inflating step factor, |mu| > lambda
    /// A vertex must stay within this distance (voxels) of the voxels of each tissue it separates (three
    /// where more meet): so no other tissue, nor one of its own, is deeper than this where it sits.
    double max_depth_voxels = 0.5;
    /// Triangles sharing no vertex keep at least this distance (voxels of the smallest spacing), unless
    /// they were closer to begin with: layers keep a thickness.
    double min_gap_voxels = 0.1;
    double min_angle_deg = 2.0;        ///< no move may create an angle below this (unless not worse)
    double max_normal_change_deg = 30; ///< one move may tilt a triangle at most this much (no folds)
    /// After the Taubin pairs, passes that pull each patch vertex onto the image's own estimate of its
    /// interface (the zero level of the difference of its two tissues' blurred indicators,
    /// surface/detail/label_field.h), each move held to the image and checked like the others (0: none).
    /// Taubin's filter keeps shapes a few voxels wide, among them the terraces of a voxelised curved
    /// surface; the fit removes most of them (spheres4 at 1 mm, vertex distance to the exact spheres:
    /// raw max 0.86 voxel, mean 0.22; Taubin alone max 0.55; with 3 fit passes max 0.53, mean 0.08).
    /// Off by default: on the 2 mm usc19-5 head (preset usc19-5-head) 3 passes lowered the final mesh's
    /// Dice against the voxels from 0.94-0.99 to 0.93-0.97 per tissue (folded anatomy at the voxel scale).
    std::size_t fit_passes = 0;
    double fit_sigma_voxels = 1.0; ///< the blur of the indicators, in voxels; in (0, 1]
};

/// What smooth() did.
struct SmoothReport {
    std::size_t iterations = 0;
    std::size_t moves = 0;             ///< vertex moves made (full or halved steps)
    std::size_t refused_by_image = 0;  ///< moves the voxel evidence refused (even halved)
    std::size_t refused_by_checks = 0; ///< moves refused as invalid (fold, intersection, gap, shape)
    std::size_t fit_moves = 0;         ///< of `moves`, those of the fit passes
    std::size_t fixed_vertices = 0;    ///< junction-curve corners, never moved
    double mean_displacement_mm = 0;   ///< over all vertices, from start to end
    double max_displacement_mm = 0;
};

/// Smooths `complex` in place by Taubin's lambda|mu filter with uniform (umbrella) weights: vertices
/// inside a patch move along their normal by the normal part of the step towards the mean of their
/// neighbours (no tangential sliding: flat places stay, shapes stay); vertices on a junction curve towards the
/// mean of their two curve neighbours (1-D smoothing along the curve, so they stay on it); corners of
/// junction curves stay. The net move of each lambda|mu pair is held to `image`
/// (SmoothOptions::max_depth_voxels; a refused move is tried at half length) and to the rules of a single
/// triangle (no degenerate triangle, no new small angle, no tilt beyond SmoothOptions::max_normal_change_deg;
/// offenders' vertices go back to where the pair found them and try half their move once more). The net move of every
/// SmoothOptions::pairs_per_check pairs is then checked against the complex (no intersection, no gap closing, no closed
/// wedge, no triangle turned by more than the tilt limit times the pairs, at most 90 degrees: see
/// surface/detail/complex_editor.h): all moves are made together, the offending ones put back and tried
/// once more at half length, so the topology and validity never change. Then SmoothOptions::fit_passes move patch
/// vertices (not junction curves) towards the image's sub-voxel interface, checked the same way. Runs on OpenMP
/// threads; the result does not depend on their number.
/// @pre  `complex` passes check_complex() and lies over `image` (as extract_interfaces() makes it)
/// @post it still passes check_complex(); triangles and connectivity unchanged
/// @throws InputError when options are out of range
SmoothReport smooth(InterfaceComplex& complex, const LabelImage& image, const SmoothOptions& options = {},
                    const Progress& progress = {});

} // namespace tissuemesh::surface

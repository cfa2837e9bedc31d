// The cross-section of a solved model coloured by a field (the potential, |E|), with a colour bar in its
// units and the tissue outlines on top.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/tet_mesh.h"
#include "render/canvas.h"

namespace tissuemesh::render {

/// Options for render_field_section(). Lengths in mm.
struct FieldSectionOptions {
    std::size_t width_px = 960, height_px = 800; ///< the colour bar takes the right 170 px
    int axis = 2;                                ///< plane normal: 0 x (sagittal), 1 y (coronal), 2 z (axial)
    bool at_centre = true;                       ///< the plane through the centre of the mesh's bounding box
    double position_mm = 0;                      ///< else the plane axis = position_mm
    std::string quantity = "potential";          ///< the colour bar's caption
    std::string unit = "V"; ///< the values' SI unit (the bar's ticks are in it, 3 significant digits)
    /// Percent of the values left out of the colour range at each end (spikes under electrodes would leave the
    /// rest of the picture in one colour); values beyond it take the end colours. 0: the field's full range.
    double clip_percent = 0;
    bool outlines = true; ///< tissue interfaces and the outer boundary in black
    std::string title;
};

/// What render_field_section() drew.
struct FieldSectionReport {
    double position_mm = 0; ///< where the plane lies along its axis
    std::size_t tets_cut = 0;
    std::size_t outline_segments = 0;
    double field_min = 0, field_max = 0;   ///< over the whole field (every value given), SI unit
    double colour_min = 0, colour_max = 0; ///< the colour bar's ends, SI unit (the field's range unless clipped)
};

/// The section of `mesh` by the plane axis = position, coloured by `values`: one per vertex (linear inside
/// each tet, as P1 elements are: the colour is interpolated per pixel) or one per tet (flat per tet).
/// Colours: field_colour() over [colour_min, colour_max]; a vertical colour bar with ticks and the caption
/// "quantity (unit)" on the right; tissue outlines (faces between tets of different labels and boundary faces
/// cut by the plane); "axis = position mm" and the title at the bottom. Non-finite values are drawn grey.
/// @throws InputError when the mesh is empty, values has neither #vertices nor #tets entries, the axis is not
///         0..2, the plane misses the mesh, clip_percent is not in [0, 50), or no value is finite
Canvas render_field_section(const TetMesh& mesh, const std::vector<double>& values,
                            const FieldSectionOptions& options = {}, FieldSectionReport* report = nullptr);

/// The perceptual colour map of the field views at t in [0, 1] (clamped): from dark violet (68, 1, 84)
/// through blue and teal to yellow (253, 231, 37), its lightness rising monotonically (after the
/// viridis design of van der Walt and Smith, as 9 anchor colours joined linearly).
Rgb field_colour(double t);

/// The t in [0, 1] of the map colour nearest to `colour` (to read a picture back), within 1/256.
double field_position(const Rgb& colour);

} // namespace tissuemesh::render

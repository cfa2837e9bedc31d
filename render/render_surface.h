// The shaded surface view of an interface complex: colour per tissue, a cut-away showing nested layers.
#pragma once

#include <cstddef>
#include <string>

#include "core/interface_complex.h"
#include "render/canvas.h"

namespace tissuemesh::render {

/// Which part of the model is taken away to look inside.
enum class CutAway {
    none,  ///< the whole model
    half,  ///< the half-space x > cut_point_mm.x
    wedge, ///< the quarter x > cut_point_mm.x and y > cut_point_mm.y (seen best from azimuth 45)
};

/// CutAway from "none", "half" or "wedge". @throws InputError on another name
CutAway parse_cut_away(const std::string& name);

/// Options for render_surface(). Angles in degrees, lengths in mm.
struct SurfaceViewOptions {
    std::size_t width_px = 800, height_px = 800;
    double azimuth_deg = 45;   ///< camera direction around +z, from +x towards +y (RAS: 0 = from the right)
    double elevation_deg = 25; ///< camera height above the xy-plane
    CutAway cut = CutAway::wedge;
    bool cut_at_centre = true; ///< cut through the centre of the bounding box (else at cut_point_mm)
    Vec3 cut_point_mm{0, 0, 0};
    bool legend = true; ///< tissue names and colours in the top-left corner
    std::string title;  ///< drawn at the bottom left when not empty
};

/// What render_surface() drew.
struct SurfaceViewReport {
    std::size_t triangles_drawn = 0; ///< triangles kept by the cut
    std::size_t triangles_cut = 0;   ///< triangles taken away with the cut region
    std::size_t pixels_covered = 0;  ///< pixels showing a tissue
};

/// Orthographic view of `complex`, fitted to the picture, with a depth buffer. A triangle is taken away
/// when its centroid lies in the cut region. A pixel shows the tissue on the camera's side of the nearest
/// triangle when that tissue is not the background: the ray then crossed the cut plane inside that
/// tissue, so the pixel stands for the cut face and is drawn flat in the tissue's colour (the surfaces are
/// not capped, this gives the same picture). Otherwise it shows the tissue behind the triangle, shaded by
/// a headlight: colour x (0.35 + 0.65 |cos|), so every pixel is a multiple of its tissue colour.
/// @throws InputError when the complex has no triangle
Canvas render_surface(const InterfaceComplex& complex, const SurfaceViewOptions& options = {},
                      SurfaceViewReport* report = nullptr);

} // namespace tissuemesh::render

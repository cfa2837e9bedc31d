// The cross-section of a tet mesh over the image slice: element edges cut by the plane, tets coloured by
// tissue, high error volume highlighted.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/label_image.h"
#include "core/tet_mesh.h"
#include "render/canvas.h"

namespace tissuemesh::render {

/// Options for render_section(). Lengths in mm.
struct SectionViewOptions {
    std::size_t width_px = 800, height_px = 800;
    int axis = 2;                ///< plane normal: 0 x (sagittal), 1 y (coronal), 2 z (axial)
    bool at_centre = true;       ///< the plane through the centre of the mesh's bounding box
    double position_mm = 0;      ///< else the plane axis = position_mm
    double tet_opacity = 0.55;   ///< tissue colour of the cut tets over the pale image slice
    double min_error_voxels = 1; ///< tets with at least this error volume (in voxels) are highlighted
    bool legend = true;
    std::string title;
};

/// What render_section() drew.
struct SectionViewReport {
    double position_mm = 0;           ///< where the plane lies along its axis
    std::size_t tets_cut = 0;         ///< tets the plane crosses
    std::size_t tets_highlighted = 0; ///< of those, tets at or over the error threshold
};

/// The section of `mesh` by the plane axis = position: the slice of `image` (when not null, nearest voxel)
/// in pale tissue colours (white blended 35% towards the tissue colour; background light grey), each cut
/// tet's polygon blended towards its tissue colour by tet_opacity, the element edges cut by the plane in
/// dark grey, and tets whose `error_volume_mm3` (when not null, #T values, e.g. from assess_elements)
/// reaches min_error_voxels x the image's voxel volume filled with error_colour. Screen: the two other axes
/// in ascending order, the second one pointing up; the mesh's extent fitted to the picture.
/// @throws InputError when the mesh is empty, the axis is not 0..2, the plane misses the mesh, or
///         error_volume_mm3 has the wrong size
Canvas render_section(const TetMesh& mesh, const LabelImage* image, const std::vector<double>* error_volume_mm3,
                      const SectionViewOptions& options = {}, SectionViewReport* report = nullptr);

} // namespace tissuemesh::render

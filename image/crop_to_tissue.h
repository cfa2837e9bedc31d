// Cropping to the tissue and padding with background, so that no tissue touches the image border.
#pragma once

#include "core/label_image.h"
#include "image/prep_report.h"

namespace tissuemesh::image {

/// Options of crop_to_tissue().
struct CropOptions {
    std::size_t pad_voxels = 2; ///< background voxels kept (or added) around the tissue on every side
    Label background = 0;       ///< the label that is not tissue; padding uses it
};

/// Replaces the image by the bounding box of its non-background voxels grown by options.pad_voxels on
/// every side (adding background beyond the old border where needed). World positions of the voxels
/// do not move: the origin follows the new first voxel.
/// @post no tissue voxel lies within pad_voxels of the border
/// @throws InputError when the image holds no tissue
PrepReport crop_to_tissue(LabelImage& image, const CropOptions& options = {});

} // namespace tissuemesh::image

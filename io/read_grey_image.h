// Reading grey-level images (CT, MRI intensities) as floats, for active contours on grey values.
#pragma once

#include <filesystem>
#include <vector>

#include "core/label_image.h"

namespace tissuemesh::io {

/// A float per voxel on a grid placed in world mm. `grid` carries the geometry only (dims, spacing,
/// origin, direction and index <-> world as in core/label_image.h); its labels are all 0.
struct GreyImage {
    LabelImage grid;
    std::vector<float> values; ///< grid.voxel_count() values, x fastest
};

/// Reads a grey-level image of any scalar voxel type (integers are converted to float). Formats: NIfTI-1
/// (`.nii`, `.nii.gz`; scl_slope/scl_inter applied, geometry as for label images: RAS mm from the
/// sform/qform), NRRD (`.nrrd`, `.nhdr`), MetaImage (`.mha`, `.mhd`) and Inrimage (`.inr`, `.inr.gz`;
/// identity direction, origin from TX/TY/TZ). Headers are checked as for label images before anything
/// is allocated. NIfTI-2 is not read yet. NIfTI values that are not finite come back as 0 (niftilib's
/// convention under ITK, as FSL and ITK tools read them); in the other formats they are an error.
/// @throws IoError when the file is missing, truncated, of an unknown extension or a wrong magic
/// @throws InputError on invalid geometry or several values per voxel, or a value that is not finite
GreyImage read_grey_image(const std::filesystem::path& path);

} // namespace tissuemesh::io

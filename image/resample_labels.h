// Resampling a label image to a new voxel size without inventing labels.
#pragma once

#include "core/label_image.h"
#include "core/progress.h"
#include "image/prep_report.h"

namespace tissuemesh::image {

enum class ResampleMethod {
    majority, ///< each new voxel takes the label covering most of its cell (exact overlap volumes)
    nearest,  ///< each new voxel takes the label of the old voxel containing its centre
};

/// Options of resample_labels().
struct ResampleOptions {
    Vec3 spacing_mm{1, 1, 1}; ///< new voxel size along i, j, k (mm), each > 0
    ResampleMethod method = ResampleMethod::majority;
};

/// Resamples onto a grid of the new spacing covering the same box: new dims = max(1, round(old extent /
/// new spacing)) per axis, the first cell starting at the old first cell's corner, same direction.
/// Majority ties go to a non-background label when one is tied (thin tissues survive), else the smaller.
/// @throws InputError for a spacing that is not positive and finite, or a result over 2^31 voxels
PrepReport resample_labels(LabelImage& image, const ResampleOptions& options, const Progress& progress = {},
                           Label background = 0);

} // namespace tissuemesh::image

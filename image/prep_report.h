// What a clean-up operation changed: every operation in image/ (relabel, crop, resample, islands,
// holes, largest component) returns one of these so that tools can log and summarise it.
#pragma once

#include <map>
#include <string>

#include "core/label_image.h"

namespace tissuemesh::image {

struct PrepReport {
    std::string step;   ///< "relabel", "crop-pad", "resample", ...
    std::string detail; ///< one line: what was done, in the user's terms
    Dims dims_before{0, 0, 0};
    Dims dims_after{0, 0, 0};
    std::map<Label, std::size_t> voxels_before; ///< voxel count per label before the step
    std::map<Label, std::size_t> voxels_after;  ///< ... and after it
    std::size_t changed_voxels = 0;             ///< voxels whose label changed (same grid only; 0 otherwise)
};

/// Starts a report: step name, dims and counts of `image` before the step.
PrepReport begin_report(const std::string& step, const LabelImage& image);
/// Completes it with the dims and counts after the step.
void finish_report(PrepReport& report, const LabelImage& image);

} // namespace tissuemesh::image

// Relabelling and merging tissues.
#pragma once

#include <map>
#include <vector>

#include "core/label_image.h"
#include "image/prep_report.h"

namespace tissuemesh::image {

/// Replaces every voxel label `from` by `mapping[from]` (all at once, so 1:2,2:1 swaps). Names follow
/// the new labels: a target without a name takes the source's name.
/// @pre  every source label of `mapping` occurs in the image
/// @throws InputError naming the first source label that does not occur, and the labels that do
PrepReport relabel(LabelImage& image, const std::map<Label, Label>& mapping);

/// Merges the tissues of `group` into its first label: merge_labels(image, {4, 5}) turns 5 into 4.
/// @pre  group has at least two labels, all present in the image
/// @throws InputError otherwise
PrepReport merge_labels(LabelImage& image, const std::vector<Label>& group);

} // namespace tissuemesh::image

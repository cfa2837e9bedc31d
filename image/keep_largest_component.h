// Keeping only the largest connected piece of chosen tissues (e.g. one brain, one skull).
#pragma once

#include <vector>

#include "core/label_image.h"
#include "image/connected_components.h"
#include "image/prep_report.h"

namespace tissuemesh::image {

/// For each label in `tissues`, keeps its largest component (ties: the first in memory order) and
/// gives every other component of it the label it shares most faces with (ties: the smaller label).
/// @pre  every label of `tissues` occurs in the image
/// @throws InputError naming the first label that does not
PrepReport keep_largest_component(LabelImage& image, const std::vector<Label>& tissues,
                                  Connectivity connectivity = Connectivity::faces6);

} // namespace tissuemesh::image

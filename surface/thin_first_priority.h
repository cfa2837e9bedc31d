// A priority for extraction that keeps thin tissues whole without naming them: every tissue ranked by its
// mean thickness in the image, the thinnest first.
#pragma once

#include <map>

#include "core/label_image.h"

namespace tissuemesh::surface {

/// Priorities for ExtractOptions::priority: each tissue (every label but `background`) gets a higher
/// priority the thinner it is, thickness being 2 * volume / surface in voxels (a sheet t voxels thick scores
/// about t; its voxel faces towards other labels or the image's outside count as surface). Ties: the smaller
/// label ranks higher. So wherever an ambiguous cube leaves two tissues both unable to connect through it, the
/// thinner one does, and a one-voxel layer (CSF between skull and brain) stays in one piece.
/// @throws InputError when the image is empty
std::map<Label, int> thin_first_priority(const LabelImage& image, Label background = 0);

} // namespace tissuemesh::surface

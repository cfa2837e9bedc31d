// Connected components of equal-label voxels, in linear time (union-find over the label array).
#pragma once

#include <cstdint>
#include <vector>

#include "core/label_image.h"

namespace tissuemesh::image {

/// Which voxels count as neighbours: sharing a face (6) or a face, an edge or a corner (26).
enum class Connectivity { faces6 = 6, full26 = 26 };

/// Components of an image: every voxel belongs to exactly one, and all its voxels share a label.
struct Components {
    std::vector<std::uint32_t> component; ///< #voxels: component id of each voxel (ids in scan order)
    std::vector<Label> label;             ///< #components: the label of each component
    std::vector<std::size_t> size;        ///< #components: voxel count of each component
    std::vector<bool> touches_border;     ///< #components: whether a voxel lies on the image border

    std::size_t count() const { return label.size(); }
};

/// Splits the image into maximal connected sets of equal-label voxels. Ids follow the first voxel of
/// each component in memory order (deterministic).
/// @throws InputError when the image has 2^32 voxels or more
Components find_components(const LabelImage& image, Connectivity connectivity);

} // namespace tissuemesh::image

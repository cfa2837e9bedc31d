// Reassigning whole components to the label around them (islands, holes, stray pieces). Internal.
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "core/label_image.h"
#include "image/connected_components.h"

namespace tissuemesh::image::detail {

/// For each component in `selected`, how many face contacts it has with each label outside it,
/// counted on the image as it is (so simultaneous reassignments do not influence each other);
/// with `skip_selected`, contacts with other selected components are not counted.
std::vector<std::map<Label, std::size_t>> surrounding_labels(const LabelImage& image, const Components& components,
                                                             const std::vector<std::uint32_t>& selected,
                                                             bool skip_selected = false);

/// The most frequent label of `histogram`; ties go to the smallest label. `fallback` when empty.
Label most_common(const std::map<Label, std::size_t>& histogram, Label fallback);

/// Sets every voxel of component selected[n] to new_labels[n]; returns the voxels that changed.
std::size_t assign_components(LabelImage& image, const Components& components,
                              const std::vector<std::uint32_t>& selected, const std::vector<Label>& new_labels);

/// Reassigns each selected component to its most common surrounding label, counting only contacts with
/// unselected components when it has any (so that it joins a piece that stays); unchanged when it has
/// no surroundings (it fills the image). Returns the voxels that changed.
std::size_t absorb_components(LabelImage& image, const Components& components,
                              const std::vector<std::uint32_t>& selected);

} // namespace tissuemesh::image::detail

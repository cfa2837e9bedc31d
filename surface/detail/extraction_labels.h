// What both extractions (marching cubes and surface nets) do before they look at a cube: which label
// each image label becomes, and whether the options make sense for the image.
#pragma once

#include <map>
#include <set>
#include <vector>

#include "core/label_image.h"

namespace tissuemesh::surface::detail {

/// The labels an extraction works with.
struct ExtractionLabels {
    std::vector<Label> map;  ///< 65 536 entries: the label each image label becomes (itself, or the background)
    std::set<Label> tissues; ///< the labels left in the image other than the background
};

/// The label each image label becomes (65 536 entries): itself when `tissues` is empty or holds it, else
/// `background`. Checks nothing (prepare_extraction() does).
std::vector<Label> kept_label_map(const std::vector<Label>& tissues, Label background);

/// Maps every label outside `tissues` (when not empty) to `background` and checks the options.
/// `max_priority_side`: the largest image side the priority rule can key (0: no limit).
/// @throws InputError when the image is empty, `background` is among `tissues`, a chosen tissue is absent,
///         nothing but background remains, a priority names a label that is neither a kept tissue nor the
///         background, or (with a priority) an image side exceeds `max_priority_side`
ExtractionLabels prepare_extraction(const LabelImage& image, const std::vector<Label>& tissues, Label background,
                                    const std::map<Label, int>& priority, std::size_t max_priority_side,
                                    const char* what);

} // namespace tissuemesh::surface::detail

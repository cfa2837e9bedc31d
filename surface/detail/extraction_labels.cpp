#include "surface/detail/extraction_labels.h"

#include <algorithm>

#include "core/error.h"

namespace tissuemesh::surface::detail {
namespace {

/// The label each image label becomes: itself when kept, `background` otherwise.
std::vector<Label> label_map(const LabelImage& image, const std::vector<Label>& tissues, Label background,
                             const char* what)
{
    if (tissues.empty()) return kept_label_map(tissues, background);
    const std::map<Label, std::size_t> present = count_labels(image);
    for (const Label tissue : std::set<Label>(tissues.begin(), tissues.end())) {
        if (tissue == background)
            throw InputError(concat(what, ": tissue ", tissue,
                                    " is also the background label; "
                                    "choose another background or drop it from the tissue list"));
        if (!present.contains(tissue))
            throw InputError(concat(what, ": tissue ", tissue,
                                    " does not occur in the image; "
                                    "check the tissue list against tm-info"));
    }
    return kept_label_map(tissues, background);
}

} // namespace

std::vector<Label> kept_label_map(const std::vector<Label>& tissues, Label background)
{
    std::vector<Label> map(std::size_t{1} << 16);
    const std::set<Label> kept(tissues.begin(), tissues.end());
    for (std::size_t l = 0; l < map.size(); ++l)
        map[l] = tissues.empty() || kept.contains(static_cast<Label>(l)) ? static_cast<Label>(l) : background;
    return map;
}

ExtractionLabels prepare_extraction(const LabelImage& image, const std::vector<Label>& tissues, Label background,
                                    const std::map<Label, int>& priority, std::size_t max_priority_side,
                                    const char* what)
{
    if (image.empty()) throw InputError(concat(what, ": the image has no voxels; give a non-empty image"));
    ExtractionLabels labels;
    labels.map = label_map(image, tissues, background, what);
    for (const auto& [label, count] : count_labels(image))
        if (labels.map[label] != background) labels.tissues.insert(labels.map[label]);
    if (labels.tissues.empty())
        throw InputError(concat(what, ": the image holds only background (label ", background,
                                "); there is no tissue to extract. Check --background and --tissues"));
    if (!priority.empty() && max_priority_side > 0 &&
        std::max({image.dims()[0], image.dims()[1], image.dims()[2]}) > max_priority_side)
        throw InputError(concat(what, ": the image has a side over ", max_priority_side,
                                " voxels, too large for the priority rule's vertex keys; crop the image or "
                                "drop the priority"));
    for (const auto& [label, value] : priority)
        if (!labels.tissues.contains(label) && label != background)
            throw InputError(concat(what, ": priority given for label ", label, " (priority ", value,
                                    "), which is not a tissue of the image; check the priority list against "
                                    "tm-info"));
    return labels;
}

} // namespace tissuemesh::surface::detail

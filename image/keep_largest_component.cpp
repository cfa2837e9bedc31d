#include "image/keep_largest_component.h"

#include <algorithm>

#include "core/error.h"
#include "image/detail/reassign.h"

namespace tissuemesh::image {

PrepReport keep_largest_component(LabelImage& image, const std::vector<Label>& tissues, Connectivity connectivity)
{
    PrepReport report = begin_report("keep-largest", image);
    for (const Label label : tissues)
        if (!report.voxels_before.contains(label))
            throw InputError(
                concat("keep-largest: label ", label, " is not in the image; check the labels with tm-info"));
    const Components components = find_components(image, connectivity);
    std::map<Label, std::uint32_t> largest;
    for (std::uint32_t c = 0; c < components.count(); ++c) {
        const Label label = components.label[c];
        if (std::find(tissues.begin(), tissues.end(), label) == tissues.end()) continue;
        const auto found = largest.find(label);
        if (found == largest.end() || components.size[c] > components.size[found->second]) largest[label] = c;
    }
    std::vector<std::uint32_t> dropped;
    for (std::uint32_t c = 0; c < components.count(); ++c) {
        const auto found = largest.find(components.label[c]);
        if (found != largest.end() && found->second != c) dropped.push_back(c);
    }
    report.changed_voxels = detail::absorb_components(image, components, dropped);
    report.detail = concat(dropped.size(), " smaller components of the chosen tissues (", report.changed_voxels,
                           " voxels) given to their surrounding tissue");
    finish_report(report, image);
    return report;
}

} // namespace tissuemesh::image

#include "image/remove_islands.h"

#include "core/error.h"
#include "image/detail/reassign.h"

namespace tissuemesh::image {

PrepReport remove_islands(LabelImage& image, const RemoveIslandsOptions& options)
{
    PrepReport report = begin_report("remove-islands", image);
    // Islands surrounded only by other islands can be left as new, merged islands: repeat a few rounds.
    const std::vector<Label> original = image.labels();
    std::size_t removed = 0;
    for (int round = 0; round < 8; ++round) {
        const Components components = find_components(image, options.connectivity);
        std::vector<std::uint32_t> islands;
        for (std::uint32_t c = 0; c < components.count(); ++c)
            if (components.label[c] != options.background && components.size[c] < options.min_voxels)
                islands.push_back(c);
        const std::size_t changed = detail::absorb_components(image, components, islands);
        if (changed == 0) break;
        removed += islands.size();
    }
    for (std::size_t v = 0; v < original.size(); ++v) report.changed_voxels += original[v] != image.labels()[v];
    report.detail = concat(removed, " islands under ", options.min_voxels, " voxels (", report.changed_voxels,
                           " voxels) given to their surrounding tissue");
    finish_report(report, image);
    return report;
}

} // namespace tissuemesh::image

#include "image/remove_islands.h"

#include "core/error.h"
#include "image/detail/reassign.h"

namespace tissuemesh::image {

PrepReport remove_islands(LabelImage& image, const RemoveIslandsOptions& options)
{
    PrepReport report = begin_report("remove-islands", image);
    const Components components = find_components(image, options.connectivity);
    std::vector<std::uint32_t> islands;
    for (std::uint32_t c = 0; c < components.count(); ++c)
        if (components.label[c] != options.background && components.size[c] < options.min_voxels) islands.push_back(c);
    report.changed_voxels = detail::absorb_components(image, components, islands);
    report.detail = concat(islands.size(), " islands under ", options.min_voxels, " voxels (",
                           report.changed_voxels, " voxels) given to their surrounding tissue");
    finish_report(report, image);
    return report;
}

} // namespace tissuemesh::image

#include "image/fill_holes.h"

#include <algorithm>

#include "core/error.h"
#include "image/connected_components.h"
#include "image/detail/reassign.h"

namespace tissuemesh::image {

PrepReport fill_holes(LabelImage& image, const FillHolesOptions& options)
{
    PrepReport report = begin_report("fill-holes", image);
    const Components components = find_components(image, Connectivity::faces6);
    std::vector<std::uint32_t> holes;
    for (std::uint32_t c = 0; c < components.count(); ++c)
        if (components.label[c] == options.background && !components.touches_border[c] &&
            (options.under_voxels == 0 || components.size[c] < options.under_voxels))
            holes.push_back(c);
    const auto surroundings = detail::surrounding_labels(image, components, holes);

    std::vector<std::uint32_t> filled;
    std::vector<Label> targets;
    for (std::size_t n = 0; n < holes.size(); ++n) {
        const bool allowed =
            options.tissues.empty() ||
            std::all_of(surroundings[n].begin(), surroundings[n].end(), [&](const auto& entry) {
                return std::find(options.tissues.begin(), options.tissues.end(), entry.first) != options.tissues.end();
            });
        if (!allowed || surroundings[n].empty()) continue;
        filled.push_back(holes[n]);
        targets.push_back(detail::most_common(surroundings[n], options.background));
    }
    report.changed_voxels = detail::assign_components(image, components, filled, targets);
    report.detail = concat(filled.size(), " of ", holes.size(), " enclosed background cavities",
                           options.under_voxels > 0 ? concat(" under ", options.under_voxels, " voxels") : "",
                           " filled (", report.changed_voxels, " voxels)");
    finish_report(report, image);
    return report;
}

} // namespace tissuemesh::image

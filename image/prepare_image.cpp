#include "image/prepare_image.h"

#include <cmath>

#include "core/error.h"
#include "image/crop_to_tissue.h"
#include "image/fill_holes.h"
#include "image/keep_largest_component.h"
#include "image/relabel.h"
#include "image/remove_islands.h"

namespace tissuemesh::image {
namespace {

void validate(const PrepOptions& options)
{
    if (options.spacing_mm)
        for (int a = 0; a < 3; ++a)
            if (const double s = (*options.spacing_mm)[a]; !std::isfinite(s) || s <= 0)
                throw InputError(concat("spacing ", format_mm(s), " mm along axis ", a,
                                        ": it must be a positive number (e.g. --spacing-mm 1 or 1,1,1.5)"));
    for (const auto& group : options.merge)
        if (group.size() < 2)
            throw InputError(concat("merge needs at least two labels (e.g. 4,5 merges 5 into 4); got ", group.size()));
}

} // namespace

std::vector<PrepReport> prepare_image(LabelImage& image, const PrepOptions& options, const Progress& progress)
{
    validate(options);
    std::vector<PrepReport> reports;
    const auto done = [&](PrepReport report) {
        progress.info(report.step, report.detail);
        reports.push_back(std::move(report));
    };
    if (!options.relabel.empty()) done(relabel(image, options.relabel));
    for (const auto& group : options.merge) done(merge_labels(image, group));
    if (options.spacing_mm)
        done(resample_labels(image, {.spacing_mm = *options.spacing_mm, .method = options.resample_method}, progress,
                             options.background));
    if (!options.keep_largest.empty()) done(keep_largest_component(image, options.keep_largest));
    if (options.remove_islands_voxels > 0)
        done(remove_islands(image, {.min_voxels = options.remove_islands_voxels, .background = options.background}));
    if (options.fill_holes)
        done(fill_holes(image, {.background = options.background,
                                .tissues = options.fill_holes_tissues,
                                .under_voxels = options.fill_holes_under_voxels}));
    if (options.crop_pad_voxels)
        done(crop_to_tissue(image, {.pad_voxels = *options.crop_pad_voxels, .background = options.background}));
    return reports;
}

} // namespace tissuemesh::image

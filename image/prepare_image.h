// The clean-up step as one call: the operations of image/ applied in a fixed order.
#pragma once

#include <map>
#include <optional>
#include <vector>

#include "core/label_image.h"
#include "core/progress.h"
#include "image/prep_report.h"
#include "image/resample_labels.h"

namespace tissuemesh::image {

/// What prepare_image() does; every field's default skips its operation.
struct PrepOptions {
    std::map<Label, Label> relabel;                            ///< 1. label -> new label, all at once
    std::vector<std::vector<Label>> merge;                     ///< 2. groups merged into their first label
    std::optional<Vec3> spacing_mm;                            ///< 3. resample to this voxel size (mm)
    ResampleMethod resample_method = ResampleMethod::majority; ///< ... with this rule
    std::vector<Label> keep_largest;                           ///< 4. tissues cut down to their largest piece
    std::size_t remove_islands_voxels = 0;                     ///< 5. remove islands under this many voxels (0: no)
    bool fill_holes = false;                                   ///< 6. fill background cavities inside tissue
    std::vector<Label> fill_holes_tissues;      ///< ... only those enclosed by these tissues (empty: any)
    std::size_t fill_holes_under_voxels = 0;    ///< ... only those under this many voxels (0: any size)
    std::optional<std::size_t> crop_pad_voxels; ///< 7. crop to the tissue, pad by this many voxels
    Label background = 0;                       ///< the label outside every tissue
};

/// Applies the requested operations in the order of the numbers above: labels are settled first, the
/// grid next (so island sizes and padding count output voxels), then the topology clean-ups, and the
/// crop last (so the padding is exact). Returns one report per operation applied, in that order.
/// @throws InputError for bad options (zero spacing, a label not in the image, a merge of one label)
///         before the image is changed by the failing step
std::vector<PrepReport> prepare_image(LabelImage& image, const PrepOptions& options, const Progress& progress = {});

} // namespace tissuemesh::image

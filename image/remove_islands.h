// Removing tiny islands: small disconnected pieces of a tissue that would become meshing debris.
#pragma once

#include "core/label_image.h"
#include "image/connected_components.h"
#include "image/prep_report.h"

namespace tissuemesh::image {

/// Options of remove_islands().
struct RemoveIslandsOptions {
    std::size_t min_voxels = 10;                        ///< components under this many voxels are removed
    Connectivity connectivity = Connectivity::faces6;   ///< what joins voxels into one component
    Label background = 0;                               ///< never removed (its small pieces are holes: fill_holes())
};

/// Gives every tissue component under options.min_voxels voxels the label it shares most faces with
/// (ties: the smaller label). All islands are decided on the input image, so the result does not depend
/// on scan order.
/// @post no non-background component under min_voxels remains that had a neighbour
PrepReport remove_islands(LabelImage& image, const RemoveIslandsOptions& options = {});

} // namespace tissuemesh::image

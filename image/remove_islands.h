// Removing tiny islands: small disconnected pieces of a tissue that would become meshing debris.
#pragma once

#include "core/label_image.h"
#include "image/connected_components.h"
#include "image/prep_report.h"

namespace tissuemesh::image {

/// Options of remove_islands().
struct RemoveIslandsOptions {
    std::size_t min_voxels = 10;                      ///< components under this many voxels are removed
    Connectivity connectivity = Connectivity::full26; ///< what joins voxels into one component (26: a layer
                                                      ///< touching only through edges stays whole)
    Label background = 0;                             ///< never removed (its small pieces are holes: fill_holes())
};

/// Gives every tissue component under options.min_voxels voxels the label it shares most faces with,
/// preferring pieces that stay (ties: the smaller label). All islands of a round are decided on the
/// image as it was, so the result does not depend on scan order; rounds repeat (at most 8) while
/// islands merged with each other are still too small.
/// @post no non-background component under min_voxels remains, unless it fills the image or 8 rounds
///       were not enough
PrepReport remove_islands(LabelImage& image, const RemoveIslandsOptions& options = {});

} // namespace tissuemesh::image

// Filling holes: background cavities enclosed in tissue (not connected to the image border).
#pragma once

#include <vector>

#include "core/label_image.h"
#include "image/prep_report.h"

namespace tissuemesh::image {

/// Options of fill_holes().
struct FillHolesOptions {
    Label background = 0;       ///< the label whose enclosed pieces are holes
    std::vector<Label> tissues; ///< fill only holes surrounded by these tissues alone (empty: any)
};

/// A hole is a face-connected (6) piece of background that does not reach the image border. Each hole
/// (whose surroundings are all in options.tissues, when given) takes the label it shares most faces
/// with (ties: the smaller label).
/// @post with options.tissues empty, all background is connected to the image border
PrepReport fill_holes(LabelImage& image, const FillHolesOptions& options = {});

} // namespace tissuemesh::image

// Where refine() puts a new node in a tet: geometric centres or the first tissue change along rays.
#pragma once

#include <array>
#include <optional>

#include "core/label_image.h"
#include "core/vec3.h"
#include "volume/refine.h"

namespace tissuemesh::volume::detail {

/// The tissue of the voxel whose cell holds `world_mm` (nearest centre), `background` outside the image.
Label voxel_label_at(const LabelImage& image, const Vec3& world_mm, Label background);

/// The new node for the tet with corners `corners` (world mm) by `placement`; material-change strategies
/// return the centroid when no ray meets a change. With `interior`, the point is pulled into the tet so
/// that each barycentric weight is at least 0.05 (constrained mode: never on a face).
Vec3 place_node(const LabelImage& image, const std::array<Vec3, 4>& corners, Placement placement, Label background,
                bool interior);

} // namespace tissuemesh::volume::detail

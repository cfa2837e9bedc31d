// VoxelEvidence: may a surface vertex be here, by the label image? A vertex separating some tissues must
// stay within a given distance (in voxels) of the voxels of each of them (of three, where more meet):
// deeper inside any one tissue, or inside another tissue, is where the image says no such interface is.
#pragma once

#include <vector>

#include "core/label_image.h"

namespace tissuemesh::surface::detail {

class VoxelEvidence {
public:
    /// `depth_voxels` in (0, 1]: the ball of this radius (index space) around a vertex must reach the
    /// voxels of each of its tissues (three of them where more meet). Outside the image counts as `background`.
    VoxelEvidence(const LabelImage& image, Label background, double depth_voxels);

    /// True when the image allows a vertex between `tissues` at `position_mm`.
    bool allows(const Vec3& position_mm, const std::vector<Label>& tissues) const;

private:
    const LabelImage& image_;
    Label background_;
    double depth_;
};

} // namespace tissuemesh::surface::detail

// LabelField: where, between two tissues, the label image puts their interface to sub-voxel precision.
// Each tissue's indicator (1 in its voxels, 0 elsewhere) blurred by a Gaussian of `sigma_voxels`; the
// interface between tissues a and b is the zero level of blur(a) - blur(b). On a voxelised sphere this level
// lies within a few hundredths of a voxel of the exact surface, where the terraced marching-cubes surface is
// up to 0.87 voxel off: smoothing pulls its vertices onto it (surface/smooth.cpp).
#pragma once

#include <optional>

#include "core/label_image.h"

namespace tissuemesh::surface::detail {

class LabelField {
public:
    /// `sigma_voxels` in (0, 1]: the blur, per axis in voxels of that axis; wider averages out more of the
    /// voxel terraces (spheres4: level within 0.27 voxel of the exact spheres at 1, 0.4 at 0.6). Where a
    /// third tissue has more than 1% of the blur's weight (thin layers, junctions) it would pull the level
    /// towards it (0.3 voxel for a one-voxel layer at sigma 1), so there `narrow_sigma` is used, and
    /// where that one too reaches a third tissue (layers one voxel thick), no step is given.
    /// Outside the image counts as `background`.
    LabelField(const LabelImage& image, Label background, double sigma_voxels);

    /// The move (mm) from `position_mm` to the zero level of blur(a) - blur(b) by one Newton step along
    /// its gradient, at most `max_step_voxels` long; none where neither tissue is near (flat field) or a
    /// third tissue is within the narrow blur.
    std::optional<Vec3> step_to_interface(const Vec3& position_mm, Label a, Label b, double max_step_voxels) const;

private:
    static constexpr double narrow_sigma = 0.6;
    static constexpr double third_tissue_share = 0.01;

    const LabelImage& image_;
    Label background_;
    double sigma_; ///< voxels summed per axis: 3 sigma on either side (the Gaussian beyond is about 1%)
};

} // namespace tissuemesh::surface::detail

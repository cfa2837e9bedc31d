// Potential fields for active contours (surface/snake.h): a scalar on a voxel grid, positive inside the
// sought region and negative outside, whose zero level is the boundary a snake settles on. Sampled by
// trilinear interpolation in world mm.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "core/label_image.h"

namespace tissuemesh::surface {

/// A float per voxel on the grid of an image (same dims, spacing, origin and direction as the image it
/// was made from; index <-> world as in core/label_image.h). Outside the grid the field takes the value of
/// the nearest border voxel.
class PotentialField {
public:
    PotentialField() = default;
    /// @throws InputError when `values` does not hold one value per voxel of `geometry`
    PotentialField(const LabelImage& geometry, std::vector<float> values);

    /// Trilinear interpolation at a world point (mm).
    double value(const Vec3& world_mm) const;
    /// Gradient (per mm, world axes) of the trilinear interpolant at a world point.
    Vec3 gradient(const Vec3& world_mm) const;
    /// Continuous voxel index of a world point.
    Vec3 world_to_index(const Vec3& world_mm) const;
    /// World point (mm) of a continuous voxel index; the inverse of world_to_index().
    Vec3 index_to_world(const Vec3& index) const;
    /// Axis-aligned world box {min, max} of the voxel centres where the field is positive (the region);
    /// nothing when no voxel is.
    std::optional<std::array<Vec3, 2>> positive_bounds_mm() const;

    const Dims& dims() const { return dims_; }
    const Vec3& spacing_mm() const { return spacing_mm_; }
    double smallest_spacing_mm() const;
    const std::vector<float>& values() const { return values_; }

private:
    double at(std::int64_t i, std::int64_t j, std::int64_t k) const;
    Dims dims_{0, 0, 0};
    Vec3 spacing_mm_{1, 1, 1};
    Vec3 origin_mm_{0, 0, 0};
    Mat3 direction_ = identity_matrix();
    std::vector<float> values_;
};

/// The voxels of `tissue` and everything it encloses: 1 for every voxel that cannot be reached from
/// outside the image through 6-connected voxels of other labels (so nested tissues count as inside).
/// One char per voxel, x fastest.
/// @throws InputError when the image has no voxel of `tissue`
std::vector<char> enclosed_region(const LabelImage& image, Label tissue);

/// The indicator of `region` (one char per voxel, 1 inside) smoothed by a Gaussian of standard deviation
/// `sigma_mm` (separable, truncated at 3 sigma, per axis in that axis' voxels), minus 0.5: its zero level
/// is the blurred region boundary, near the voxel faces between inside and outside.
/// @throws InputError when sigma_mm is negative or `region` does not match the image
PotentialField label_potential(const LabelImage& image, const std::vector<char>& region, double sigma_mm);

/// A grey-level image (one float per voxel of `geometry`) smoothed by a Gaussian of `sigma_mm` (0: none),
/// minus `iso`: positive where the value exceeds the iso value (`bright_inside`, e.g. bone in CT) or, with
/// `bright_inside` false, where it is below. The zero level is the iso-surface of the smoothed image.
/// @throws InputError when sizes disagree, sigma_mm is negative or iso is not finite
PotentialField grey_potential(const LabelImage& geometry, const std::vector<float>& values, double iso, double sigma_mm,
                              bool bright_inside = true);

/// Gaussian smoothing in place of a float volume on `dims` with per-axis standard deviations in voxels
/// (0: that axis is left alone); borders replicate the edge voxels.
void gaussian_smooth(std::vector<float>& values, const Dims& dims, const Vec3& sigma_voxels);

} // namespace tissuemesh::surface

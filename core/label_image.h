// LabelImage: a tissue-classified voxel grid placed in world millimetres.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/vec3.h"

namespace tissuemesh {

using Label = std::uint16_t;
using Dims = std::array<std::size_t, 3>; ///< voxels along i, j, k (i varies fastest in memory)
using Index3 = std::array<std::int64_t, 3>;

/// Tissue names by label ("scalp", "skull", ...). Labels without a name print as their number.
using TissueNames = std::map<Label, std::string>;

/// A label per voxel on a regular grid, with the geometry ITK and NIfTI define:
///     world_mm = origin_mm + direction * diag(spacing_mm) * index        (world: RAS mm, as NIfTI)
/// where `index` is the (continuous) voxel index and voxel centres sit at integer indices.
/// The direction matrix holds the unit axis directions as columns (row-major storage).
/// Invariant: labels().size() == dims[0] * dims[1] * dims[2].
class LabelImage {
public:
    LabelImage() = default;
    /// @throws InputError when a dimension is zero, the voxel count overflows, a spacing is not a
    ///         positive finite number, or the direction matrix is not orthonormal.
    LabelImage(const Dims& dims, const Vec3& spacing_mm, const Vec3& origin_mm = {0, 0, 0},
               const Mat3& direction = identity_matrix(), Label fill = 0);

    const Dims& dims() const { return dims_; }
    const Vec3& spacing_mm() const { return spacing_mm_; }
    const Vec3& origin_mm() const { return origin_mm_; }
    const Mat3& direction() const { return direction_; }
    void set_origin_mm(const Vec3& origin_mm) { origin_mm_ = origin_mm; }

    std::size_t voxel_count() const { return labels_.size(); }
    double voxel_volume_mm3() const { return spacing_mm_[0] * spacing_mm_[1] * spacing_mm_[2]; }
    bool empty() const { return labels_.empty(); }

    std::size_t linear_index(std::size_t i, std::size_t j, std::size_t k) const
    {
        return i + dims_[0] * (j + dims_[1] * k);
    }
    bool contains(const Index3& index) const
    {
        return index[0] >= 0 && index[1] >= 0 && index[2] >= 0 && static_cast<std::size_t>(index[0]) < dims_[0] &&
               static_cast<std::size_t>(index[1]) < dims_[1] && static_cast<std::size_t>(index[2]) < dims_[2];
    }
    Label at(std::size_t i, std::size_t j, std::size_t k) const { return labels_[linear_index(i, j, k)]; }
    Label& at(std::size_t i, std::size_t j, std::size_t k) { return labels_[linear_index(i, j, k)]; }
    /// The label at `index`, or `outside` where the index lies beyond the image.
    Label at_or(const Index3& index, Label outside) const
    {
        if (!contains(index)) return outside;
        return at(static_cast<std::size_t>(index[0]), static_cast<std::size_t>(index[1]),
                  static_cast<std::size_t>(index[2]));
    }

    const std::vector<Label>& labels() const { return labels_; }
    std::vector<Label>& labels() { return labels_; }

    /// World position (mm) of a continuous voxel index.
    Vec3 index_to_world(const Vec3& index) const;
    /// Continuous voxel index of a world position (mm); the inverse of index_to_world().
    Vec3 world_to_index(const Vec3& world_mm) const;
    /// Axis-aligned world bounding box of the voxel cells (not just the centres): {min, max}.
    std::array<Vec3, 2> world_bounds_mm() const;

    TissueNames& names() { return names_; }
    const TissueNames& names() const { return names_; }
    /// The tissue's name, or its number when it has none.
    std::string name_of(Label label) const;

private:
    Dims dims_{0, 0, 0};
    Vec3 spacing_mm_{1, 1, 1};
    Vec3 origin_mm_{0, 0, 0};
    Mat3 direction_ = identity_matrix();
    std::vector<Label> labels_;
    TissueNames names_;
};

/// Checks spacing, dims and direction as the LabelImage constructor does; `what` names the source
/// (a file name) in the message.
/// @throws InputError naming `what`, the faulty value and the fix.
void validate_geometry(const std::string& what, const Dims& dims, const Vec3& spacing_mm, const Mat3& direction);

/// Labels present in the image, ascending, with their voxel counts.
std::map<Label, std::size_t> count_labels(const LabelImage& image);

} // namespace tissuemesh

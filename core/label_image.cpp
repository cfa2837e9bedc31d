#include "core/label_image.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace tissuemesh {

void validate_geometry(const std::string& what, const Dims& dims, const Vec3& spacing_mm, const Mat3& direction)
{
    std::size_t count = 1;
    for (int axis = 0; axis < 3; ++axis) {
        if (dims[axis] == 0)
            throw InputError(concat(what, ": dimension ", axis,
                                    " is 0; an image needs at least one voxel "
                                    "along every axis"));
        if (count > std::numeric_limits<std::size_t>::max() / dims[axis] || dims[axis] > (std::size_t{1} << 31))
            throw InputError(concat(what, ": dimensions ", dims[0], " x ", dims[1], " x ", dims[2],
                                    " overflow the voxel count; the header is corrupt"));
        count *= dims[axis];
        const double s = spacing_mm[axis];
        if (!std::isfinite(s) || s <= 0)
            throw InputError(concat(what, ": spacing along axis ", axis, " is ", format_mm(s),
                                    " mm; it must be a positive finite number. Fix the header "
                                    "(e.g. tm-prep --spacing) or the writer that produced it"));
    }
    // Columns of the direction matrix must be orthonormal (ITK requires the same).
    for (int a = 0; a < 3; ++a) {
        for (int b = a; b < 3; ++b) {
            double d = 0;
            for (int r = 0; r < 3; ++r) d += direction[3 * r + a] * direction[3 * r + b];
            const double expected = a == b ? 1.0 : 0.0;
            if (!std::isfinite(d) || std::abs(d - expected) > 1e-4)
                throw InputError(concat(what, ": the direction matrix is not orthonormal (columns ", a, " and ", b,
                                        "); the orientation in the header is corrupt"));
        }
    }
}

LabelImage::LabelImage(const Dims& dims, const Vec3& spacing_mm, const Vec3& origin_mm, const Mat3& direction,
                       Label fill)
    : dims_(dims), spacing_mm_(spacing_mm), origin_mm_(origin_mm), direction_(direction)
{
    validate_geometry("label image", dims, spacing_mm, direction);
    labels_.assign(dims[0] * dims[1] * dims[2], fill);
}

Vec3 LabelImage::index_to_world(const Vec3& index) const
{
    const Vec3 scaled{index[0] * spacing_mm_[0], index[1] * spacing_mm_[1], index[2] * spacing_mm_[2]};
    return origin_mm_ + multiply(direction_, scaled);
}

Vec3 LabelImage::world_to_index(const Vec3& world_mm) const
{
    // The direction matrix is orthonormal, so its inverse is its transpose.
    const Vec3 local = multiply(transpose(direction_), world_mm - origin_mm_);
    return {local[0] / spacing_mm_[0], local[1] / spacing_mm_[1], local[2] / spacing_mm_[2]};
}

std::array<Vec3, 2> LabelImage::world_bounds_mm() const
{
    Vec3 lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
    Vec3 hi{-lo[0], -lo[1], -lo[2]};
    for (int corner = 0; corner < 8; ++corner) {
        Vec3 index;
        for (int axis = 0; axis < 3; ++axis)
            index[axis] = (corner >> axis & 1) ? static_cast<double>(dims_[axis]) - 0.5 : -0.5;
        const Vec3 p = index_to_world(index);
        for (int axis = 0; axis < 3; ++axis) {
            lo[axis] = std::min(lo[axis], p[axis]);
            hi[axis] = std::max(hi[axis], p[axis]);
        }
    }
    return {lo, hi};
}

std::string LabelImage::name_of(Label label) const
{
    const auto found = names_.find(label);
    return found != names_.end() && !found->second.empty() ? found->second : std::to_string(label);
}

std::map<Label, std::size_t> count_labels(const LabelImage& image)
{
    std::vector<std::size_t> histogram(std::size_t{std::numeric_limits<Label>::max()} + 1, 0);
    for (const Label label : image.labels()) ++histogram[label];
    std::map<Label, std::size_t> counts;
    for (std::size_t label = 0; label < histogram.size(); ++label)
        if (histogram[label] > 0) counts[static_cast<Label>(label)] = histogram[label];
    return counts;
}

} // namespace tissuemesh

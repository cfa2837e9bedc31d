// NIfTI-2 voxels and geometry, read without ITK (ITK 5.2's NIfTI library knows NIfTI-1 only).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "io/detail/nifti_header.h"
#include "io/detail/voxel_decode.h"

namespace tissuemesh::io::detail {
namespace fs = std::filesystem;

namespace {

VoxelType nifti_voxel_type(const std::string& name, int datatype)
{
    switch (datatype) {
    case 2: return VoxelType::u8;
    case 4: return VoxelType::i16;
    case 8: return VoxelType::i32;
    case 16: return VoxelType::f32;
    case 64: return VoxelType::f64;
    case 256: return VoxelType::i8;
    case 512: return VoxelType::u16;
    case 768: return VoxelType::u32;
    case 1024: return VoxelType::i64;
    case 1280: return VoxelType::u64;
    default: break;
    }
    throw IoError(
        concat(name, ": unsupported NIfTI datatype ", datatype, "; save the label map as an integer or float image"));
}

struct Geometry {
    Vec3 spacing{1, 1, 1};
    Vec3 origin{0, 0, 0};
    Mat3 direction = identity_matrix();
};

/// The sform's columns are the axis vectors scaled by the spacing; its last column is the origin.
Geometry sform_geometry(const NiftiHeader& h)
{
    Geometry g;
    for (int column = 0; column < 3; ++column) {
        const Vec3 axis{h.srow[column], h.srow[4 + column], h.srow[8 + column]};
        g.spacing[column] = norm(axis);
        for (int row = 0; row < 3; ++row)
            g.direction[3 * row + column] = g.spacing[column] > 0 ? axis[row] / g.spacing[column] : 0;
    }
    g.origin = {h.srow[3], h.srow[7], h.srow[11]};
    return g;
}

/// The qform: a rotation given by a unit quaternion (b, c, d; a = sqrt(1 - b² - c² - d²)), the third
/// axis flipped when pixdim[0] (qfac) is negative, spacing from pixdim.
Geometry qform_geometry(const NiftiHeader& h)
{
    const double b = h.quatern[0], c = h.quatern[1], d = h.quatern[2];
    const double a = std::sqrt(std::max(0.0, 1.0 - (b * b + c * c + d * d)));
    const double qfac = h.pixdim[0] < 0 ? -1.0 : 1.0;
    Geometry g;
    g.direction = {
        a * a + b * b - c * c - d * d, 2 * (b * c - a * d),           qfac * 2 * (b * d + a * c),
        2 * (b * c + a * d),           a * a + c * c - b * b - d * d, qfac * 2 * (c * d - a * b),
        2 * (b * d - a * c),           2 * (c * d + a * b),           qfac * (a * a + d * d - b * b - c * c)};
    g.spacing = {h.pixdim[1], h.pixdim[2], h.pixdim[3]};
    g.origin = {h.quatern[3], h.quatern[4], h.quatern[5]};
    return g;
}

bool orthogonal(const Mat3& m)
{
    for (int a = 0; a < 3; ++a)
        for (int b = a + 1; b < 3; ++b)
            if (std::abs(m[a] * m[b] + m[3 + a] * m[3 + b] + m[6 + a] * m[6 + b]) > 1e-4) return false;
    return true;
}

Geometry nifti_geometry(const NiftiHeader& h)
{
    if (h.sform_code > 0) {
        const Geometry sform = sform_geometry(h);
        if (orthogonal(sform.direction) || h.qform_code <= 0) return sform;
    }
    if (h.qform_code > 0) return qform_geometry(h);
    Geometry g;
    g.spacing = {h.pixdim[1], h.pixdim[2], h.pixdim[3]};
    return g;
}

bool host_is_big_endian()
{
    const std::uint16_t probe = 1;
    unsigned char first;
    std::memcpy(&first, &probe, 1);
    return first == 0;
}

} // namespace

LabelImage read_nifti2(const fs::path& path, const NiftiHeader& h, const BeforeVoxels& before_voxels)
{
    const std::string name = path.string();
    const VoxelType type = nifti_voxel_type(name, h.datatype);
    const Geometry g = nifti_geometry(h);
    validate_geometry(name, h.dims, g.spacing, g.direction);
    const std::uint64_t needed = checked_voxel_bytes(name, h.dims, voxel_type_size(type));
    if (before_voxels) before_voxels(h.dims, g.spacing, voxel_type_size(type));
    std::vector<unsigned char> bytes = read_payload(path, static_cast<std::uint64_t>(h.vox_offset), needed);
    const bool big_endian = h.swapped != host_is_big_endian();
    LabelImage image(h.dims, g.spacing, g.origin, g.direction);
    // NIfTI: a slope of 0 means "no scaling".
    if (h.scl_slope != 0 && (h.scl_slope != 1 || h.scl_inter != 0)) {
        bytes = rescale_to_float64(bytes.data(), type, big_endian, image.voxel_count(), h.scl_slope, h.scl_inter);
        decode_labels(name, bytes.data(), VoxelType::f64, host_is_big_endian(), image);
    } else {
        decode_labels(name, bytes.data(), type, big_endian, image);
    }
    return image;
}

} // namespace tissuemesh::io::detail

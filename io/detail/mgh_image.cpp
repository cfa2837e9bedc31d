#include "io/detail/mgh_image.h"

#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/error.h"

namespace tissuemesh::io::detail {
namespace {

constexpr std::size_t header_bytes = 284;

/// Big-endian fields of the header, read by offset.
class BigEndianHeader {
public:
    explicit BigEndianHeader(std::vector<unsigned char> bytes) : bytes_(std::move(bytes)) {}

    std::int32_t int32(std::size_t at) const { return static_cast<std::int32_t>(word(at, 4)); }
    std::int16_t int16(std::size_t at) const { return static_cast<std::int16_t>(word(at, 2)); }
    double float32(std::size_t at) const
    {
        const auto bits = static_cast<std::uint32_t>(word(at, 4));
        float value = 0;
        std::memcpy(&value, &bits, sizeof value);
        return value;
    }

private:
    std::uint64_t word(std::size_t at, std::size_t size) const
    {
        std::uint64_t value = 0;
        for (std::size_t b = 0; b < size; ++b) value = value << 8 | bytes_[at + b];
        return value;
    }
    std::vector<unsigned char> bytes_;
};

VoxelType voxel_type(const std::string& name, std::int32_t code)
{
    switch (code) {
    case 0: return VoxelType::u8;
    case 4: return VoxelType::i16;
    case 1: return VoxelType::i32;
    case 3: return VoxelType::f32;
    case 10: return VoxelType::u16;
    default:
        throw InputError(concat(name, ": MGH voxel type ", code,
                                " is not a label type; save the labels as uchar (0), "
                                "short (4), int (1), ushort (10) or float (3), e.g. mri_convert -odt uchar"));
    }
}

Dims dims_of(const std::string& name, const BigEndianHeader& header)
{
    Dims dims{};
    for (std::size_t axis = 0; axis < 3; ++axis) {
        const std::int32_t value = header.int32(4 + 4 * axis);
        if (value <= 0)
            throw InputError(
                concat(name, ": MGH dimension ", axis, " is ", value, "; the header is corrupt, write the file again"));
        dims[axis] = static_cast<std::size_t>(value);
    }
    const std::int32_t frames = header.int32(16);
    if (frames != 1)
        throw InputError(concat(name, ": ", frames,
                                " frames per voxel; a label image has one (extract the frame "
                                "holding the labels, e.g. mri_convert --frame 0)"));
    return dims;
}

} // namespace

LabelImage read_mgh(const std::filesystem::path& path, const BeforeVoxels& before_voxels)
{
    const std::string name = path.string();
    const std::uint64_t available = uncompressed_size(path);
    if (available < header_bytes)
        throw IoError(concat(name, ": ", available,
                             " bytes are too few for an MGH header (284); the file is truncated "
                             "or not an MGH volume"));
    const BigEndianHeader header(read_payload(path, 0, header_bytes));
    if (header.int32(0) != 1)
        throw IoError(concat(name, ": MGH version ", header.int32(0),
                             " is not 1; this is not an MGH/MGZ volume (or is "
                             "corrupt), check the file or its extension"));
    const Dims dims = dims_of(name, header);
    const VoxelType type = voxel_type(name, header.int32(20));
    Vec3 spacing{1, 1, 1}, centre{0, 0, 0};
    // Rows of Mdc: the world direction of each voxel axis (nibabel's default when goodRASFlag is 0).
    std::array<Vec3, 3> axes{Vec3{-1, 0, 0}, Vec3{0, 0, 1}, Vec3{0, -1, 0}};
    if (header.int16(28) != 0)
        for (std::size_t i = 0; i < 3; ++i) {
            spacing[i] = header.float32(30 + 4 * i);
            centre[i] = header.float32(78 + 4 * i);
            for (std::size_t j = 0; j < 3; ++j) axes[i][j] = header.float32(42 + 12 * i + 4 * j);
        }
    // nibabel scales the rows as stored; a row that is not a unit vector scales that axis's spacing.
    Mat3 direction{};
    Vec3 spacing_mm{};
    Vec3 origin = centre;
    for (std::size_t i = 0; i < 3; ++i) {
        const double length = norm(axes[i]);
        if (!(length > 0) || !std::isfinite(length))
            throw InputError(concat(name, ": the direction of voxel axis ", i,
                                    " in the MGH header is zero or not finite; "
                                    "the header is corrupt, write the file again"));
        if (!(spacing[i] > 0) || !std::isfinite(spacing[i]))
            throw InputError(concat(name, ": MGH spacing along axis ", i, " is ", spacing[i],
                                    " mm; it must be a positive "
                                    "number, fix the header (mri_convert -vs)"));
        spacing_mm[i] = spacing[i] * length;
        for (std::size_t j = 0; j < 3; ++j) {
            direction[3 * j + i] = axes[i][j] / length;
            origin[j] -= axes[i][j] * spacing[i] * static_cast<double>(dims[i]) / 2.0;
        }
    }
    validate_geometry(name, dims, spacing_mm, direction);
    const std::uint64_t needed = checked_voxel_bytes(name, dims, voxel_type_size(type));
    require_payload(name, header_bytes + needed, available);
    if (before_voxels) before_voxels(dims, spacing_mm, voxel_type_size(type));
    const std::vector<unsigned char> voxels = read_payload(path, header_bytes, needed);
    LabelImage image(dims, spacing_mm, origin, direction);
    decode_labels(name, voxels.data(), type, true, image);
    return image;
}

} // namespace tissuemesh::io::detail

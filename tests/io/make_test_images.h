// Test inputs generated in code: a small label image with known geometry, and hand-made (possibly
// broken) files in the formats read_label_image() reads. Header-only: test_io and test_io_cli share it.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/label_image.h"

namespace tissuemesh::testing {

/// A 5 x 4 x 3 image, anisotropic spacing, axes permuted and flipped (i -> -y, j -> +x, k -> +z),
/// labels i + 2 j + 7 k (0..25) times `scale` so that scale > 10 needs uint16.
inline LabelImage make_oriented_image(Label scale = 1)
{
    const Mat3 direction{0, 1, 0, -1, 0, 0, 0, 0, 1};
    LabelImage image({5, 4, 3}, {0.5, 1.25, 2.0}, {-10.5, 20.25, 3.0}, direction);
    for (std::size_t k = 0; k < 3; ++k)
        for (std::size_t j = 0; j < 4; ++j)
            for (std::size_t i = 0; i < 5; ++i) image.at(i, j, k) = static_cast<Label>((i + 2 * j + 7 * k) * scale);
    return image;
}

inline void write_bytes(const std::filesystem::path& path, const std::vector<unsigned char>& bytes)
{
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

/// Stores `value` at `offset` in the host's byte order, or reversed when `swap`.
template <typename T>
void put(std::vector<unsigned char>& bytes, std::size_t offset, T value, bool swap = false)
{
    std::memcpy(bytes.data() + offset, &value, sizeof(T));
    if (swap)
        for (std::size_t b = 0; b < sizeof(T) / 2; ++b) std::swap(bytes[offset + b], bytes[offset + sizeof(T) - 1 - b]);
}

/// Fields of a hand-made single-file NIfTI-1 image (little-endian, as on the test machines).
struct NiftiSpec {
    std::int16_t dims[4] = {3, 2, 2, 2}; ///< dim[0] (rank), then the sizes
    float spacing[3] = {1, 1, 1};
    std::int16_t datatype = 2; ///< 2 uint8, 4 int16, 16 float32, 512 uint16, 128 RGB
    std::int16_t bitpix = 8;
    std::int16_t vectors = 1;              ///< dim[5]: values per voxel (rank becomes 5 when > 1)
    float scale_slope = 1;                 ///< scl_slope: value = slope * stored + intercept
    float scale_intercept = 0;             ///< scl_inter
    float quatern[6] = {0, 0, 0, 0, 0, 0}; ///< qform: quatern_b, c, d, qoffset_x, y, z
    float qfac = 1;                        ///< pixdim[0]: -1 flips the third axis
    bool swapped = false;                  ///< write the header in the other byte order
    char magic[4] = {'n', '+', '1', '\0'};
};

/// A NIfTI-1 file: 348-byte header, 4 bytes of extension flag, voxel data from byte 352. `data` is
/// written as given (it may be shorter than the header asks for, to make truncated files).
inline void write_nifti(const std::filesystem::path& path, const NiftiSpec& spec,
                        const std::vector<unsigned char>& data)
{
    std::vector<unsigned char> bytes(352, 0);
    put<std::int32_t>(bytes, 0, 348, spec.swapped);
    const std::int16_t rank = spec.vectors > 1 ? 5 : spec.dims[0];
    put<std::int16_t>(bytes, 40, rank, spec.swapped);
    for (int axis = 1; axis <= 7; ++axis)
        put<std::int16_t>(bytes, 40 + 2 * axis,
                          axis <= 3   ? spec.dims[axis]
                          : axis == 5 ? spec.vectors
                                      : 1,
                          spec.swapped);
    put<std::int16_t>(bytes, 70, spec.datatype, spec.swapped);
    put<std::int16_t>(bytes, 72, spec.bitpix, spec.swapped);
    put<float>(bytes, 76, spec.qfac, spec.swapped);
    for (int axis = 0; axis < 3; ++axis) put<float>(bytes, 80 + 4 * axis, spec.spacing[axis], spec.swapped);
    put<float>(bytes, 108, 352.0f, spec.swapped); // vox_offset
    put<float>(bytes, 112, spec.scale_slope, spec.swapped);
    put<float>(bytes, 116, spec.scale_intercept, spec.swapped);
    put<std::int16_t>(bytes, 252, 1, spec.swapped); // qform_code: scanner
    for (int n = 0; n < 6; ++n) put<float>(bytes, 256 + 4 * n, spec.quatern[n], spec.swapped);
    std::memcpy(bytes.data() + 344, spec.magic, 4);
    bytes.insert(bytes.end(), data.begin(), data.end());
    write_bytes(path, bytes);
}

/// A NIfTI-2 file (540-byte header, data from byte 544), uint8, identity qform, spacing 1 x 2 x 3.
/// With `srow` (12 values), the sform (code 2) is set as well; `quatern` and `qfac` as in NiftiSpec.
inline void write_nifti2(const std::filesystem::path& path, const std::int64_t (&dims)[3],
                         const std::vector<unsigned char>& data, const std::vector<double>& srow = {},
                         const std::vector<double>& quatern = {0, 0, 0, 0, 0, 0}, double qfac = 1)
{
    std::vector<unsigned char> bytes(544, 0);
    put<std::int32_t>(bytes, 0, 540);
    std::memcpy(bytes.data() + 4, "n+2\0\r\n\032\n", 8);
    put<std::int16_t>(bytes, 12, 2); // datatype uint8
    put<std::int16_t>(bytes, 14, 8); // bitpix
    put<std::int64_t>(bytes, 16, 3);
    for (int axis = 0; axis < 3; ++axis) put<std::int64_t>(bytes, 24 + 8 * axis, dims[axis]);
    for (int axis = 3; axis < 7; ++axis) put<std::int64_t>(bytes, 24 + 8 * axis, 1);
    put<double>(bytes, 104, qfac); // pixdim[0]
    for (std::size_t n = 0; n < 6; ++n) put<double>(bytes, 352 + 8 * n, quatern[n]);
    for (int axis = 0; axis < 3; ++axis) put<double>(bytes, 112 + 8 * axis, axis + 1.0);
    put<std::int64_t>(bytes, 168, 544); // vox_offset
    put<double>(bytes, 176, 1.0);       // scl_slope
    put<std::int32_t>(bytes, 344, 1);   // qform_code
    if (srow.size() == 12) {
        put<std::int32_t>(bytes, 348, 2); // sform_code
        for (std::size_t n = 0; n < 12; ++n) put<double>(bytes, 400 + 8 * n, srow[n]);
    }
    bytes.insert(bytes.end(), data.begin(), data.end());
    write_bytes(path, bytes);
}

/// `count` little-endian values of type T as bytes.
template <typename T>
std::vector<unsigned char> voxel_bytes(const std::vector<T>& values)
{
    std::vector<unsigned char> bytes(values.size() * sizeof(T));
    if (!values.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
}

} // namespace tissuemesh::testing

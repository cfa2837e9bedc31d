// Shared by the label-image readers: voxel types, size checks made before any allocation, and the
// conversion of stored voxel values to labels with one-line errors naming the offending voxel.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/label_image.h"
#include "io/read_label_image.h"

namespace tissuemesh::io::detail {

/// How one voxel is stored on disk.
enum class VoxelType { u8, i8, u16, i16, u32, i32, u64, i64, f32, f64 };

/// Bytes per voxel of `type`.
std::size_t voxel_type_size(VoxelType type);
/// The raw + JSON name of `type`: "uint8", "int16", "float32", ...
std::string voxel_type_name(VoxelType type);
/// Parses "uint8", "int8", "uint16", "int16", "uint32", "int32", "uint64", "int64", "float32", "float64".
std::optional<VoxelType> parse_voxel_type(const std::string& name);

/// Number of voxels of `dims`, checked: throws InputError naming `file` when a dimension is 0 or the
/// product (times `bytes_per_voxel`) overflows 64 bits.
std::uint64_t checked_voxel_bytes(const std::string& file, const Dims& dims, std::size_t bytes_per_voxel);

/// ReadImageOptions::before_voxels: called before the voxels are allocated (may be empty).
using BeforeVoxels = io::BeforeVoxels;

/// Throws IoError ("truncated") naming `file` when `needed_bytes` > `available_bytes`. Readers call
/// it before allocating, so a corrupt header cannot make them allocate more than the file holds.
void require_payload(const std::string& file, std::uint64_t needed_bytes, std::uint64_t available_bytes);

/// Size in bytes of the file's content after gzip decompression (the file size for uncompressed
/// files), counted by streaming: nothing is kept in memory.
/// @throws IoError when the file cannot be read or its gzip stream is corrupt
std::uint64_t uncompressed_size(const std::filesystem::path& path);

/// Reads `bytes` bytes starting at byte `offset` of the (gzip-decompressed) content of `path`.
/// Call require_payload() first: this allocates `bytes` at once.
/// @throws IoError when the file ends early or cannot be read
std::vector<unsigned char> read_payload(const std::filesystem::path& path, std::uint64_t offset, std::uint64_t bytes);

/// True when the file starts with the gzip magic bytes.
bool is_gzip_file(const std::filesystem::path& path);

/// Converts the image's voxels, stored as `type` (byte order `big_endian`) in `bytes`, to labels in
/// `image` (decoded in place: no second label buffer).
/// @throws InputError naming `file`, the first offending voxel (i, j, k) and its value when a value is
///         not an integer (NaN, fractional), negative, or above 65535
void decode_labels(const std::string& file, const unsigned char* bytes, VoxelType type, bool big_endian,
                   LabelImage& image);

/// The voxels of `grid` (its dims give the count), stored as `type` in `bytes`, as floats (grey values),
/// x fastest.
/// @throws InputError naming `file` and the first voxel (i, j, k) whose value is not finite
std::vector<float> to_finite_floats(const std::string& file, const unsigned char* bytes, VoxelType type,
                                    bool big_endian, const LabelImage& grid);

/// The `count` values stored as `type` in `bytes`, times `slope` plus `intercept`, as float64 in host
/// byte order (NIfTI's scl_slope/scl_inter), ready for decode_labels(..., VoxelType::f64, host order).
std::vector<unsigned char> rescale_to_float64(const unsigned char* bytes, VoxelType type, bool big_endian,
                                              std::size_t count, double slope, double intercept);

/// Bytes per voxel a writer uses for `image`: 1 when every label fits uint8, else 2.
std::size_t label_width(const LabelImage& image);

/// The labels as little-endian unsigned integers of `width` bytes (1 or 2), x fastest.
std::string encode_labels(const LabelImage& image, std::size_t width);

} // namespace tissuemesh::io::detail

// Inrimage (.inr, .inr.gz): a small reader and writer of our own.
//
// The header is text in 256-byte blocks: "#INRIMAGE-4#{" on the first line, then KEY=VALUE lines, then
// newlines up to "##}" closing the last block; voxel data (x fastest) follows. Keys used:
//   XDIM, YDIM, ZDIM   voxels per axis (ZDIM defaults to 1)
//   VDIM               values per voxel; only 1 is a label map
//   TYPE               "unsigned fixed", "signed fixed" or "float"
//   PIXSIZE            "8 bits", "16 bits", "32 bits" or "64 bits"
//   CPU                byte order: decm, alpha, pc (little endian); sun, sgi (big endian)
//   VX, VY, VZ         spacing in mm (default 1)
//   TX, TY, TZ         origin in mm (also read as XO, YO, ZO; default 0)
// Inrimage has no orientation: the direction is the identity, and world = origin + spacing * index.
#pragma once

#include <filesystem>
#include <string>

#include "core/label_image.h"
#include "io/detail/voxel_decode.h"

namespace tissuemesh::io::detail {

/// What an Inrimage header says about the voxels that follow it.
struct InrimageLayout {
    Dims dims{0, 0, 0};
    Vec3 spacing_mm{1, 1, 1};
    Vec3 origin_mm{0, 0, 0};
    VoxelType type = VoxelType::u8;
    bool big_endian = false;
    std::size_t header_bytes = 0; ///< the voxel data starts here (a multiple of 256)
};

/// Reads and checks the header of a .inr or .inr.gz file (one value per voxel, valid geometry).
/// @throws IoError on a wrong magic or an unreadable header; InputError on invalid content
InrimageLayout read_inrimage_layout(const std::filesystem::path& path);

/// Reads a .inr or .inr.gz file (gzip detected by content).
/// @throws IoError on a wrong magic, an unreadable header or truncated data; InputError on invalid
///         content (vector images, bad spacing, non-integer or out-of-range labels)
LabelImage read_inrimage(const std::filesystem::path& path, const BeforeVoxels& before_voxels = {});

/// Writes `image` (uint8 when every label fits, else uint16, little endian) to `path`, gzip-compressed
/// when `compress`. `name` is the file name for messages.
/// @throws InputError when the direction is not the identity (Inrimage cannot store it)
/// @throws IoError when the file cannot be written
void write_inrimage(const LabelImage& image, const std::filesystem::path& path, const std::string& name, bool compress);

} // namespace tissuemesh::io::detail

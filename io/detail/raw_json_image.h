// Raw voxels described by a JSON sidecar (.json), the simplest exchange format with numpy/MATLAB.
//
// Schema (keys not listed are ignored, so provenance can sit next to the description):
//   {
//     "dims":       [nx, ny, nz],                voxels per axis, x fastest in the raw file (required)
//     "spacing":    [sx, sy, sz],                mm, positive (required)
//     "origin":     [x, y, z],                   mm, world (RAS) position of voxel (0,0,0) (default 0)
//     "direction":  [[r0], [r1], [r2]],          3x3 rows; the columns are the unit axis directions in
//                                                RAS, as in LabelImage (default identity)
//     "dtype":      "uint8" | "int8" | "uint16" | "int16" | "uint32" | "int32" | "float32" | "float64"
//                   (also "uint64", "int64"; required)
//     "byte_order": "little" | "big"             (default "little")
//     "raw_file":   "head.raw",                  path relative to the JSON's folder; may be gzip-compressed
//                                                (required)
//     "labels":     {"1": "scalp", ...}          tissue names (optional)
//   }
// World coordinates: world = origin + direction * diag(spacing) * index, RAS mm.
#pragma once

#include <filesystem>
#include <string>

#include "core/label_image.h"
#include "io/detail/voxel_decode.h"

namespace tissuemesh::io::detail {

/// Reads the sidecar at `path` and the raw file it names.
/// @throws IoError on invalid JSON, a missing or truncated raw file; InputError on missing or invalid
///         keys and invalid voxel values
LabelImage read_raw_json_image(const std::filesystem::path& path, const BeforeVoxels& before_voxels = {});

/// Writes `<stem>.raw` (uint8 or uint16, little endian) next to `path`, then the sidecar `path`, both
/// atomically; the sidecar holds the tissue names.
void write_raw_json_image(const LabelImage& image, const std::filesystem::path& path);

} // namespace tissuemesh::io::detail

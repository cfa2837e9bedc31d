// FreeSurfer's MGH volumes (.mgh, and .mgz: the same gzip-compressed), read as label images.
//
// Layout (big endian): a 284-byte header, then the voxels, x fastest, then optional tags (ignored):
//   int32 version (1); int32 width, height, depth, frames; int32 type (0 uint8, 4 int16, 1 int32,
//   3 float32, 10 uint16); int32 degrees of freedom; int16 goodRASFlag; float32 spacing[3];
//   float32 Mdc[3][3] (row i: the world direction of voxel axis i); float32 centre[3] (RAS mm).
// World coordinates as nibabel computes them (MGHHeader.get_affine):
//   world = centre + sum_i Mdc[i] * spacing[i] * (index_i - dims_i / 2)
// so voxel index dims/2 (not (dims-1)/2) sits at the centre. When goodRASFlag is 0 the geometry fields are not
// valid and nibabel's default applies: spacing 1, Mdc rows (-1,0,0), (0,0,1), (0,-1,0), centre 0.
#pragma once

#include <filesystem>

#include "core/label_image.h"
#include "io/detail/voxel_decode.h"

namespace tissuemesh::io::detail {

/// Reads a .mgh or .mgz file (gzip detected by content).
/// @throws IoError when the file is too short for a header, is not an MGH file (version other than 1) or its
///         voxels are truncated; InputError on invalid content: dimensions, several frames, an unknown voxel
///         type, spacing that is not positive, axes that are not orthogonal, labels that are not integers in
///         0..65535. Every message names the file, the field and the fix.
LabelImage read_mgh(const std::filesystem::path& path, const BeforeVoxels& before_voxels = {});

} // namespace tissuemesh::io::detail

// The ITK adapter behind read_label_image()/write_label_image() for NIfTI, NRRD and MetaImage.
// ITK types stay in the .cpp file.
#pragma once

#include <cstdint>
#include <filesystem>

#include "core/label_image.h"
#include "io/detail/voxel_decode.h"
#include "io/read_grey_image.h"

namespace tissuemesh::io::detail {

/// Reads a scalar image through ITK's ImageIO: header first (rejecting vector and 4D images), then
/// the voxels, converted to labels with decode_labels(). Geometry is converted from ITK's LPS to RAS.
/// Slicer segment names (Segment{N}_Name / Segment{N}_LabelValue) become tissue names.
/// @param max_payload_bytes  the most voxel-data bytes the file can hold; a header asking for more is
///        rejected as truncated before anything is allocated
/// @param before_voxels  called (when set) after those checks, before the voxels are allocated
/// @throws IoError when ITK cannot read the file, InputError on invalid content
LabelImage read_itk_label_image(const std::filesystem::path& path, std::uint64_t max_payload_bytes,
                                const BeforeVoxels& before_voxels = {});

/// Reads a scalar image through ITK like read_itk_label_image(), keeping the values as floats (grey
/// levels: CT, MRI). NIfTI's scl_slope/scl_inter are applied by ITK.
/// @throws IoError when ITK cannot read the file, InputError on invalid geometry or a value that is not finite
GreyImage read_itk_grey_image(const std::filesystem::path& path, std::uint64_t max_payload_bytes);

/// Writes `image` to `path` through ITK (the format follows `path`'s extension), uint8 when every
/// label fits, else uint16; compressed where the format allows. With `slicer_segments`, tissue names
/// are written as 3D Slicer segment keys (for .seg.nrrd). `name` is the file name for messages.
/// @throws IoError when ITK cannot write
void write_itk_label_image(const LabelImage& image, const std::filesystem::path& path, const std::string& name,
                           bool slicer_segments);

} // namespace tissuemesh::io::detail

// Writers for the two-file formats ITK would name wrongly when writing to a temporary file (its data
// file name would keep the temporary name): MetaImage .mhd and NRRD .nhdr, each with a raw data file
// named after the header ("head.mhd" -> "head.mhd.raw", "head.nhdr" -> "head.nhdr.raw") so that no two
// formats share a data file. ITK reads them back.
#pragma once

#include <filesystem>

#include "core/label_image.h"

namespace tissuemesh::io::detail {

/// Writes the raw data file (uint8 or uint16, little endian) and then the header at `path` (.mhd or
/// .nhdr), both atomically. Geometry is stored in LPS as both formats expect.
/// @throws IoError when a file cannot be written
void write_detached_image(const LabelImage& image, const std::filesystem::path& path);

} // namespace tissuemesh::io::detail

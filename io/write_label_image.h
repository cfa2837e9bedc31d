// Writing label images in the formats read_label_image() reads.
#pragma once

#include <filesystem>

#include "core/label_image.h"

namespace tissuemesh::io {

/// Writes `image` atomically; the format is chosen by the extension as in read_label_image().
/// Voxels are stored as uint8 when every label fits, else uint16. Tissue names are stored where the
/// format has a place for them (.seg.nrrd segments, the raw + JSON sidecar).
/// @throws IoError when the file cannot be written or the extension is not a known format
void write_label_image(const LabelImage& image, const std::filesystem::path& path);

} // namespace tissuemesh::io

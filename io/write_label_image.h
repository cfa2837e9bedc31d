// Writing label images in the formats read_label_image() reads.
#pragma once

#include <filesystem>

#include "core/label_image.h"

namespace tissuemesh::io {

/// Writes `image` atomically (outputs are valid or absent); the format is chosen by the extension as
/// in read_label_image(), and reading the file back gives the same grid, geometry and labels.
/// Voxels are stored as uint8 when every label fits, else uint16. Compressed: .nii.gz, .nrrd,
/// .seg.nrrd, .mha, .inr.gz. Tissue names are stored where the format has a place for them: .seg.nrrd
/// (one Slicer segment per present or named label, single layer) and the raw + JSON sidecar.
/// Two-file formats write their data first, then the header: `.mhd` -> `<name>.mhd.raw`,
/// `.nhdr` -> `<name>.nhdr.raw`, `.json` -> `<stem>.raw`, next to the header.
/// Output is deterministic: the same image gives the same bytes.
/// @throws InputError when the image is empty, or when writing Inrimage and the direction is not the
///         identity (Inrimage cannot store an orientation: use .nii.gz)
/// @throws IoError when the file cannot be written or the extension is not a known format
void write_label_image(const LabelImage& image, const std::filesystem::path& path);

} // namespace tissuemesh::io

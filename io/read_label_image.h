// Reading label images: NIfTI-1/2, NRRD (and 3D Slicer .seg.nrrd), MetaImage, Inrimage, raw + JSON.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/label_image.h"

namespace tissuemesh::io {

/// Options for read_label_image().
struct ReadImageOptions {
    std::filesystem::path names_json;  ///< optional {"1": "scalp", ...}; overrides names from the file
};

/// Reads a label image; the format is chosen by the file name's extension:
/// `.nii`, `.nii.gz`, `.nrrd`, `.nhdr`, `.seg.nrrd`, `.mha`, `.mhd`, `.inr`, `.inr.gz`, `.json` (raw + JSON
/// sidecar). World coordinates are RAS millimetres for every format, as the NIfTI affine (sform/qform)
/// defines them: ITK's LPS geometry with x and y negated. Inrimage has no orientation: identity, origin
/// from its header (0 when absent). Integer voxel types of any width are accepted when every value fits uint16; float
/// images only when every value is an integer. Tissue names come from the file when it has them
/// (Slicer segments) and from `options.names_json`.
/// @post the result passes validate_geometry()
/// @throws IoError  when the file is missing, unreadable, truncated or not of the format its name says
/// @throws InputError when the content is invalid (bad spacing, fractional or too large labels, ...)
LabelImage read_label_image(const std::filesystem::path& path, const ReadImageOptions& options = {});

/// Reads a tissue-name table: a JSON object mapping label numbers to names ({"1": "scalp"}), or the
/// object under its "labels" key (the sidecars in data/samples have that shape).
/// @throws IoError / InputError on unreadable files or malformed content
TissueNames read_tissue_names(const std::filesystem::path& path);

/// The extensions read_label_image() understands, for messages and --help.
std::vector<std::string> label_image_extensions();

} // namespace tissuemesh::io

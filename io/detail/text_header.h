// Bounds on the voxel data of NRRD and MetaImage files, read from their text headers before ITK
// allocates anything.
#pragma once

#include <cstdint>
#include <filesystem>

namespace tissuemesh::io::detail {

/// The most voxel-data bytes a .nrrd/.nhdr/.seg.nrrd or .mha/.mhd file (with its detached data file)
/// can hold: the data's size on disk, times 1032 (deflate's largest ratio) when it is compressed.
/// @throws IoError on a wrong magic, a missing data file, or multi-file data (LIST or patterns)
std::uint64_t text_header_payload_bound(const std::filesystem::path& path);

} // namespace tissuemesh::io::detail

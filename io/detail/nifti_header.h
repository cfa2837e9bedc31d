// A check of NIfTI-1/2 headers made before ITK sees the file: ITK and its nifti library accept zero
// or NaN spacing, print to stderr, and allocate whatever the header asks for.
#pragma once

#include <cstdint>
#include <filesystem>

namespace tissuemesh::io::detail {

/// Checks the header of the .nii / .nii.gz file at `path`: magic and header size (NIfTI-1 or -2, either
/// byte order), one value per voxel (no 4D or vector images), positive finite spacing along the
/// image's axes, and that the (decompressed) file holds every voxel the dimensions need.
/// @returns the number of voxel-data bytes the header asks for (a bound for the reader's allocation)
/// @throws IoError on unreadable, truncated or non-NIfTI files, InputError on invalid content
std::uint64_t check_nifti_header(const std::filesystem::path& path);

} // namespace tissuemesh::io::detail

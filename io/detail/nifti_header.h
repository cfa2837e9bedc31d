// A check of NIfTI-1/2 headers made before ITK sees the file: ITK and its nifti library accept zero
// or NaN spacing, print to stderr, and allocate whatever the header asks for.
#pragma once

#include <cstdint>
#include <filesystem>

namespace tissuemesh::io::detail {

/// Checks the header of the .nii / .nii.gz file at `path`: magic and header size (NIfTI-1 or -2, either
/// byte order), one value per voxel (no 4D or vector images), positive finite spacing along the
/// image's axes, and that the (decompressed) file holds every voxel the dimensions need.
/// @returns a bound on the bytes ITK's buffer for the voxels may need: voxel count * 8, since ITK hands
///          images with scl_slope/scl_inter over as float or double whatever their stored type
/// @throws IoError on unreadable, truncated or non-NIfTI files, InputError on invalid content
std::uint64_t check_nifti_header(const std::filesystem::path& path);

} // namespace tissuemesh::io::detail

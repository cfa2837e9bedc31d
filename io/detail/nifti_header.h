// A check of NIfTI-1/2 headers made before ITK sees the file: ITK and its nifti library accept zero
// or NaN spacing, print to stderr, and allocate whatever the header asks for.
#pragma once

#include <cstdint>
#include <array>
#include <filesystem>

#include "core/label_image.h"
#include "io/detail/voxel_decode.h"

namespace tissuemesh::io::detail {

/// The fields of a NIfTI-1 or NIfTI-2 header that tissuemesh uses, in host byte order.
struct NiftiHeader {
    int version = 1;                   ///< 1 or 2
    bool swapped = false;              ///< the file's byte order is not the host's
    std::array<std::int64_t, 8> dim{}; ///< as stored: dim[0] is the number of axes
    Dims dims{1, 1, 1};                ///< dim[1..3] (1 for missing axes)
    std::array<double, 8> pixdim{};
    int datatype = 0;
    int bitpix = 0;
    std::int64_t vox_offset = 0;
    double scl_slope = 0, scl_inter = 0;
    // Orientation fields, parsed for NIfTI-2 only (ITK reads NIfTI-1's).
    int qform_code = 0, sform_code = 0;
    std::array<double, 6> quatern{};    ///< quatern_b, c, d, qoffset_x, y, z
    std::array<double, 12> srow{};      ///< srow_x, srow_y, srow_z (4 each)
    std::uint64_t max_buffer_bytes = 0; ///< bound for ITK's voxel buffer: voxels * 8, since ITK hands
                                        ///< images with scl_slope/scl_inter over as float or double
};

/// Checks the header of the .nii / .nii.gz file at `path`: magic and header size (NIfTI-1 or -2, either
/// byte order), one value per voxel (no 4D or vector images), positive finite spacing along the
/// image's axes, and that the (decompressed) file holds every voxel the dimensions need.
/// @throws IoError on unreadable, truncated or non-NIfTI files, InputError on invalid content
NiftiHeader check_nifti_header(const std::filesystem::path& path);

/// For a NIfTI-1 file of float voxels (datatype 16 or 64): throws InputError naming the first voxel
/// (i, j, k) whose stored value is not finite. niftilib, under ITK, turns such values into 0 without a
/// word, which for a label image would make broken voxels background. Streams the voxels (1 MiB at a time).
/// Does nothing for other datatypes.
void require_finite_float_voxels(const std::filesystem::path& path, const NiftiHeader& header);

/// Reads a NIfTI-2 file whose header check_nifti_header() returned (ITK 5.2 reads NIfTI-1 only).
/// Geometry from the sform (when sform_code > 0 and orthogonal), else the qform (qform_code > 0),
/// else pixdim alone; scl_slope/scl_inter are applied before the labels are checked.
/// @throws IoError on unsupported datatypes, InputError on invalid content
LabelImage read_nifti2(const std::filesystem::path& path, const NiftiHeader& header,
                       const BeforeVoxels& before_voxels = {});

} // namespace tissuemesh::io::detail

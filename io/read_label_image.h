// Reading label images: NIfTI-1/2, NRRD (and 3D Slicer .seg.nrrd), MetaImage, Inrimage, FreeSurfer MGH/MGZ, raw + JSON.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/label_image.h"

namespace tissuemesh::io {

/// Options for read_label_image().
/// Called once an image header is checked, before any voxel is allocated: dimensions, spacing (mm) and the bytes
/// per voxel of the file's type. It may throw to refuse the image.
using BeforeVoxels = std::function<void(const Dims& dims, const Vec3& spacing_mm, std::size_t file_bytes_per_voxel)>;

struct ReadImageOptions {
    std::filesystem::path
        names_json; ///< optional table of names (any format read_tissue_names() reads); overrides the file's
    /// Optional: called once the header is checked (dimensions, spacing, and that the file holds the voxels),
    /// before any voxel is allocated, with the dimensions, the spacing (mm) and the bytes per voxel of the
    /// file's type. It may throw to refuse the image: tools refuse images that need more memory than they
    /// may use (tools/memory_limit.h).
    BeforeVoxels before_voxels;
};

/// Reads a label image; the format is chosen by the file name's extension:
///   `.nii`, `.nii.gz`         NIfTI-1 or -2 (single file), either byte order; scl_slope/scl_inter applied
///   `.nrrd`, `.nhdr`          NRRD, attached or detached data, raw/gzip/ascii encodings
///   `.seg.nrrd`               3D Slicer segmentation: single-layer label maps only; Segment{N}_Name and
///                             Segment{N}_LabelValue become tissue names
///   `.mha`, `.mhd`            MetaImage
///   `.inr`, `.inr.gz`         Inrimage (see io/detail/inrimage.h for the keys read)
///   `.mgz`, `.mgh`            FreeSurfer MGH, gzip-compressed or not (aseg.mgz, ...): one frame, the world
///                             position of every voxel as nibabel gives it (io/detail/mgh_image.h)
///   `.json`                   raw voxels + JSON sidecar (schema in io/detail/raw_json_image.h); its
///                             "labels" become tissue names
/// World coordinates are RAS millimetres for every format, as the NIfTI affine (sform/qform) defines
/// them: ITK's LPS geometry with x and y negated. Inrimage has no orientation: identity direction,
/// origin from its TX/TY/TZ keys (0 when absent). Integer voxel types of any width are accepted when
/// every value fits uint16; float images only when every value is a whole number. Names from
/// `options.names_json` replace the file's names label by label.
/// Before allocating, the reader checks the header against the file: it never allocates more than
/// the (decompressed) file can hold. The library never prints: ITK's own messages are suppressed
/// (std::cerr is redirected during ITK calls, so do not read images from several threads at once).
/// @post the result passes validate_geometry()
/// @throws IoError  when the file is missing, empty, unreadable, truncated, not of the format its name
///         says (wrong magic), or has an unknown extension
/// @throws InputError when the content is invalid: zero/negative/NaN/infinite spacing, dimensions that
///         are 0 or overflow, several values per voxel (vector, RGB, 4D, multi-layer segmentations),
///         fractional, negative or too large labels (the message names the first such voxel and value)
/// Every message is one line: "<file>: <problem>; <fix>".
LabelImage read_label_image(const std::filesystem::path& path, const ReadImageOptions& options = {});

/// The voxel spacing (mm) of a label image, from its header: the checks of read_label_image() up to the voxels,
/// which are not read (nor decompressed). The same errors as read_label_image() for a bad header.
Vec3 read_label_image_spacing(const std::filesystem::path& path);

/// Reads a tissue-name table, whatever its format:
///   - JSON (a `.json` name, or text starting with '{'): an object mapping label numbers to names
///     ({"1": "scalp"}), or the object under its "labels" key (the sidecars in data/samples have that shape);
///   - a BIDS `*_dseg.tsv` (a `.tsv` name): tab-separated, a header with the columns "index" and "name";
///   - an ITK-SNAP label description file: `<label> <r> <g> <b> <alpha> <visible> <mesh> "<name>"` per line;
///   - a FreeSurfer colour table (FreeSurferColorLUT.txt): `<label> <name> <r> <g> <b> <a>` per line.
/// The last two are told apart by their first line that is neither blank nor a '#' comment (a quoted name:
/// ITK-SNAP).
/// @throws IoError on missing files, files over 16 MiB or invalid JSON; InputError when a key or line does not
///         fit its format, a label is not in 0..65535, is named twice, or a name is empty or not a string
///         ("<file> line <n>: <problem>; <the format's layout>")
TissueNames read_tissue_names(const std::filesystem::path& path);

/// The extensions read_label_image() understands, for messages and --help.
std::vector<std::string> label_image_extensions();

} // namespace tissuemesh::io

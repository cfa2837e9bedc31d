#include "io/read_grey_image.h"

#include <cmath>
#include <cstring>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/detail/inrimage.h"
#include "io/detail/itk_image_io.h"
#include "io/detail/nifti_header.h"
#include "io/detail/text_header.h"
#include "io/detail/voxel_decode.h"

namespace tissuemesh::io {

GreyImage read_grey_image(const std::filesystem::path& path)
{
    const std::string name = path.string();
    require_readable_file(path);
    if (std::filesystem::file_size(path) == 0)
        throw IoError(concat(name, ": the file is empty; write or copy it again"));
    const std::string extension = full_extension(path);
    if (extension == ".nii" || extension == ".nii.gz") {
        const detail::NiftiHeader header = detail::check_nifti_header(path);
        if (header.version == 2)
            throw IoError(concat(name, ": NIfTI-2 grey images are not read yet; save it as NIfTI-1 (e.g. with "
                                       "nibabel or 3D Slicer), or as .nrrd or .mha"));
        return detail::read_itk_grey_image(path, header.max_buffer_bytes);
    }
    if (extension == ".nrrd" || extension == ".nhdr" || extension == ".mha" || extension == ".mhd")
        return detail::read_itk_grey_image(path, detail::text_header_payload_bound(path));
    if (extension != ".inr" && extension != ".inr.gz")
        throw IoError(concat(name, ": unknown grey image format '", extension,
                             "'; use NIfTI-1 (.nii, .nii.gz), "
                             "NRRD (.nrrd, .nhdr), MetaImage (.mha, .mhd) or Inrimage (.inr, .inr.gz)"));
    const detail::InrimageLayout layout = detail::read_inrimage_layout(path);
    const std::uint64_t needed = detail::checked_voxel_bytes(name, layout.dims, detail::voxel_type_size(layout.type));
    const std::uint64_t size = detail::uncompressed_size(path);
    detail::require_payload(name, needed, size > layout.header_bytes ? size - layout.header_bytes : 0);
    const std::vector<unsigned char> bytes = detail::read_payload(path, layout.header_bytes, needed);
    GreyImage image{LabelImage(layout.dims, layout.spacing_mm, layout.origin_mm), {}};
    image.values = detail::to_finite_floats(name, bytes.data(), layout.type, layout.big_endian, image.grid);
    return image;
}

} // namespace tissuemesh::io

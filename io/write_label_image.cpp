#include "io/write_label_image.h"

#include <string>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/detail/detached_headers.h"
#include "io/detail/inrimage.h"
#include "io/detail/itk_image_io.h"
#include "io/detail/raw_json_image.h"

namespace tissuemesh::io {
namespace fs = std::filesystem;

void write_label_image(const LabelImage& image, const fs::path& path)
{
    const std::string name = path.string();
    if (image.empty()) throw InputError(concat(name, ": cannot write an empty image; it has no voxels"));
    const std::string extension = full_extension(path);
    if (extension == ".nii" || extension == ".nii.gz" || extension == ".nrrd" || extension == ".seg.nrrd" ||
        extension == ".mha") {
        // The temporary keeps the full file name as suffix, so ITK picks the format from it.
        write_atomically(path, [&](const fs::path& temporary) {
            detail::write_itk_label_image(image, temporary, name, extension == ".seg.nrrd");
        });
    } else if (extension == ".mhd" || extension == ".nhdr") {
        detail::write_detached_image(image, path);
    } else if (extension == ".inr" || extension == ".inr.gz") {
        write_atomically(path, [&](const fs::path& temporary) {
            detail::write_inrimage(image, temporary, name, extension == ".inr.gz");
        });
    } else if (extension == ".json") {
        detail::write_raw_json_image(image, path);
    } else {
        throw IoError(concat(name, ": unknown image format '", extension,
                             "'; use .nii.gz, .nii, .nrrd, .nhdr, .seg.nrrd, .mha, .mhd, .inr, .inr.gz or .json"));
    }
}

} // namespace tissuemesh::io

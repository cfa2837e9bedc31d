#include "io/write_label_image.h"

#include <string>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/detail/itk_image_io.h"

namespace tissuemesh::io {
namespace fs = std::filesystem;

void write_label_image(const LabelImage& image, const fs::path& path)
{
    const std::string name = path.string();
    if (image.empty()) throw InputError(concat(name, ": cannot write an empty image; it has no voxels"));
    const std::string extension = full_extension(path);
    if (extension == ".nii" || extension == ".nii.gz" || extension == ".nrrd" || extension == ".seg.nrrd" ||
        extension == ".mha") {
        write_atomically(path, [&](const fs::path& temporary) {
            detail::write_itk_label_image(image, temporary, name, extension == ".seg.nrrd");
        });
        return;
    }
    throw IoError(concat(name, ": unknown image format '", extension,
                         "'; use .nii.gz, .nii, .nrrd, .nhdr, .seg.nrrd, .mha, .mhd, .inr, .inr.gz or .json"));
}

} // namespace tissuemesh::io

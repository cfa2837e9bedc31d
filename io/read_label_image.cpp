#include "io/read_label_image.h"

#include <string>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/detail/inrimage.h"
#include "io/detail/itk_image_io.h"
#include "io/detail/label_tables.h"
#include "io/detail/mgh_image.h"
#include "io/detail/nifti_header.h"
#include "io/detail/raw_json_image.h"
#include "io/detail/text_header.h"
#include "io/detail/tissue_names.h"

namespace tissuemesh::io {
namespace fs = std::filesystem;

namespace {

std::string extension_list()
{
    std::string list;
    for (const std::string& extension : label_image_extensions()) list += (list.empty() ? "" : ", ") + extension;
    return list;
}

} // namespace

TissueNames read_tissue_names(const fs::path& path)
{
    require_readable_file(path);
    const std::string name = path.string();
    constexpr std::uintmax_t max_bytes = 16u << 20;
    if (fs::file_size(path) > max_bytes)
        throw IoError(concat(name, ": ", fs::file_size(path),
                             " bytes is too large for a tissue-name table (at most 16 MiB); "
                             "check that --labels names the table, not an image"));
    const std::string text = read_file_bytes(path);
    const std::size_t first = text.find_first_not_of(" \t\r\n");
    if (full_extension(path) != ".json" && (first == std::string::npos || text[first] != '{'))
        return detail::parse_label_table(text, name, detail::detect_label_table(text, full_extension(path) == ".tsv"));
    const nlohmann::json document = nlohmann::json::parse(text, nullptr, false);
    if (document.is_discarded())
        throw IoError(concat(name, ": not valid JSON; check the syntax (quotes, commas, braces)"));
    if (document.is_object() && document.contains("labels"))
        return detail::parse_tissue_names(name, document["labels"]);
    return detail::parse_tissue_names(name, document);
}

std::vector<std::string> label_image_extensions()
{
    return {".nii", ".nii.gz", ".nrrd",   ".nhdr", ".seg.nrrd", ".mha",
            ".mhd", ".inr",    ".inr.gz", ".mgz",  ".mgh",      ".json"};
}

LabelImage read_label_image(const fs::path& path, const ReadImageOptions& options)
{
    require_readable_file(path);
    const std::string name = path.string();
    if (fs::file_size(path) == 0) throw IoError(concat(name, ": the file is empty; write or copy it again"));
    const std::string extension = full_extension(path);
    LabelImage image;
    if (extension == ".nii" || extension == ".nii.gz") {
        const detail::NiftiHeader header = detail::check_nifti_header(path);
        if (header.version == 1) detail::require_finite_float_voxels(path, header);
        image = header.version == 2
                    ? detail::read_nifti2(path, header, options.before_voxels)
                    : detail::read_itk_label_image(path, header.max_buffer_bytes, options.before_voxels);
    } else if (extension == ".nrrd" || extension == ".nhdr" || extension == ".seg.nrrd" || extension == ".mha" ||
               extension == ".mhd") {
        image = detail::read_itk_label_image(path, detail::text_header_payload_bound(path), options.before_voxels);
    } else if (extension == ".inr" || extension == ".inr.gz") {
        image = detail::read_inrimage(path, options.before_voxels);
    } else if (extension == ".mgz" || extension == ".mgh") {
        image = detail::read_mgh(path, options.before_voxels);
    } else if (extension == ".json") {
        image = detail::read_raw_json_image(path, options.before_voxels);
    } else {
        throw IoError(concat(name, ": unknown image format '", extension, "'; use one of ", extension_list()));
    }
    if (!options.names_json.empty())
        for (const auto& [label, tissue] : read_tissue_names(options.names_json)) image.names()[label] = tissue;
    return image;
}

Vec3 read_label_image_spacing(const fs::path& path)
{
    struct HeaderRead {}; // thrown once the header is checked, to stop before the voxels
    Vec3 spacing{0, 0, 0};
    try {
        // Every reader calls before_voxels; were one not to, the image read in full still has its spacing.
        return read_label_image(path, {.before_voxels =
                                           [&](const Dims&, const Vec3& spacing_mm, std::size_t) {
                                               spacing = spacing_mm;
                                               throw HeaderRead{};
                                           }})
            .spacing_mm();
    } catch (const HeaderRead&) {
        return spacing;
    }
}

} // namespace tissuemesh::io

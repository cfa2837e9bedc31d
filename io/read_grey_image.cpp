#include "io/read_grey_image.h"

#include <cmath>
#include <cstring>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/detail/inrimage.h"
#include "io/detail/voxel_decode.h"

namespace tissuemesh::io {

GreyImage read_grey_image(const std::filesystem::path& path)
{
    const std::string name = path.string();
    require_readable_file(path);
    const std::string extension = full_extension(path);
    if (extension != ".inr" && extension != ".inr.gz")
        throw IoError(concat(name, ": grey-level images are read from Inrimage (.inr, .inr.gz) only; convert it "
                                   "(e.g. with ITK or 3D Slicer) or use a label image with --tissue"));
    const detail::InrimageLayout layout = detail::read_inrimage_layout(path);
    const std::uint64_t needed = detail::checked_voxel_bytes(name, layout.dims, detail::voxel_type_size(layout.type));
    const std::uint64_t size = detail::uncompressed_size(path);
    detail::require_payload(name, needed, size > layout.header_bytes ? size - layout.header_bytes : 0);
    const std::vector<unsigned char> bytes = detail::read_payload(path, layout.header_bytes, needed);
    GreyImage image{LabelImage(layout.dims, layout.spacing_mm, layout.origin_mm), {}};
    const std::size_t count = image.grid.voxel_count();
    const std::vector<unsigned char> doubles =
        detail::rescale_to_float64(bytes.data(), layout.type, layout.big_endian, count, 1, 0);
    image.values.resize(count);
    for (std::size_t v = 0; v < count; ++v) {
        double value = 0;
        std::memcpy(&value, doubles.data() + 8 * v, sizeof value);
        if (!std::isfinite(value)) {
            const Dims& d = layout.dims;
            throw InputError(concat(name, ": voxel (", v % d[0], ", ", (v / d[0]) % d[1], ", ", v / (d[0] * d[1]),
                                    ") holds ", value, "; grey values must be finite numbers"));
        }
        image.values[v] = static_cast<float>(value);
    }
    return image;
}

} // namespace tissuemesh::io

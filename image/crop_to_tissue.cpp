#include "image/crop_to_tissue.h"

#include <algorithm>

#include "core/error.h"

namespace tissuemesh::image {

PrepReport crop_to_tissue(LabelImage& image, const CropOptions& options)
{
    PrepReport report = begin_report("crop-pad", image);
    const Dims& d = image.dims();
    std::array<std::size_t, 3> lo{d[0], d[1], d[2]}, hi{0, 0, 0};
    for (std::size_t k = 0; k < d[2]; ++k)
        for (std::size_t j = 0; j < d[1]; ++j)
            for (std::size_t i = 0; i < d[0]; ++i) {
                if (image.at(i, j, k) == options.background) continue;
                const std::size_t index[3] = {i, j, k};
                for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], index[a]), hi[a] = std::max(hi[a], index[a]);
            }
    if (lo[0] > hi[0])
        throw InputError(concat("crop-pad: the image holds only background (label ", options.background,
                                "); nothing to crop to. Check the labels with tm-info"));
    const auto pad = static_cast<std::int64_t>(options.pad_voxels);
    Index3 start{};
    Dims dims{};
    for (int a = 0; a < 3; ++a) {
        start[a] = static_cast<std::int64_t>(lo[a]) - pad;
        dims[a] = hi[a] - lo[a] + 1 + 2 * options.pad_voxels;
    }
    const Vec3 origin = image.index_to_world(
        {static_cast<double>(start[0]), static_cast<double>(start[1]), static_cast<double>(start[2])});
    LabelImage cropped(dims, image.spacing_mm(), origin, image.direction(), options.background);
    for (std::size_t k = 0; k < dims[2]; ++k)
        for (std::size_t j = 0; j < dims[1]; ++j)
            for (std::size_t i = 0; i < dims[0]; ++i) {
                const Index3 source{start[0] + static_cast<std::int64_t>(i), start[1] + static_cast<std::int64_t>(j),
                                    start[2] + static_cast<std::int64_t>(k)};
                if (image.contains(source))
                    cropped.at(i, j, k) =
                        image.at(static_cast<std::size_t>(source[0]), static_cast<std::size_t>(source[1]),
                                 static_cast<std::size_t>(source[2]));
            }
    cropped.names() = image.names();
    image = std::move(cropped);
    report.detail =
        concat(report.dims_before[0], "x", report.dims_before[1], "x", report.dims_before[2], " -> ", dims[0], "x",
               dims[1], "x", dims[2], " voxels (tissue box padded by ", options.pad_voxels, ")");
    finish_report(report, image);
    return report;
}

} // namespace tissuemesh::image

#include "image/resample_labels.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace tissuemesh::image {
namespace {

/// Along one axis: for every new voxel, the old voxels its cell overlaps and the overlap as a fraction
/// of the new cell. Cells are measured in old continuous indices: old voxel i spans [i - 0.5, i + 0.5].
struct AxisOverlaps {
    std::vector<std::vector<std::pair<std::size_t, double>>> cells;
    std::vector<std::size_t> nearest; ///< the old voxel containing each new centre
};

AxisOverlaps axis_overlaps(std::size_t old_count, std::size_t new_count, double ratio)
{
    AxisOverlaps axis;
    axis.cells.resize(new_count);
    axis.nearest.resize(new_count);
    const auto last = static_cast<double>(old_count - 1);
    for (std::size_t n = 0; n < new_count; ++n) {
        const double lo = static_cast<double>(n) * ratio - 0.5, hi = lo + ratio;
        const double first = std::max(0.0, std::floor(lo + 0.5)), end = std::min(last, std::ceil(hi - 0.5));
        for (double i = first; i <= end; i += 1) {
            const double overlap = std::min(hi, i + 0.5) - std::max(lo, i - 0.5);
            if (overlap > 0) axis.cells[n].emplace_back(static_cast<std::size_t>(i), overlap / ratio);
        }
        axis.nearest[n] = static_cast<std::size_t>(std::clamp(std::round(lo + 0.5 * ratio), 0.0, last));
    }
    return axis;
}

/// The label of the largest weight; near-ties prefer a non-background label, then the smaller one.
Label heaviest(const std::vector<std::pair<Label, double>>& weights, Label background)
{
    Label best = weights.front().first;
    double best_weight = weights.front().second;
    for (const auto& [label, weight] : weights) {
        const bool tie = std::abs(weight - best_weight) <= 1e-9;
        const bool better_tie = (best == background && label != background) ||
                                ((best == background) == (label == background) && label < best);
        if ((!tie && weight > best_weight) || (tie && better_tie)) best = label, best_weight = weight;
    }
    return best;
}

using Overlaps = std::vector<std::pair<std::size_t, double>>;

/// The label covering most of the new cell whose overlaps along each axis are given; `weights` is scratch.
Label majority(const LabelImage& image, const Overlaps& x, const Overlaps& y, const Overlaps& z,
               std::vector<std::pair<Label, double>>& weights, Label background)
{
    weights.clear();
    for (const auto& [c, wz] : z)
        for (const auto& [b, wy] : y)
            for (const auto& [a, wx] : x) {
                const Label label = image.at(a, b, c);
                auto found = std::find_if(weights.begin(), weights.end(),
                                          [&](const auto& entry) { return entry.first == label; });
                if (found == weights.end()) weights.emplace_back(label, wx * wy * wz);
                else found->second += wx * wy * wz;
            }
    return heaviest(weights, background);
}

} // namespace

PrepReport resample_labels(LabelImage& image, const ResampleOptions& options, const Progress& progress,
                           Label background)
{
    PrepReport report = begin_report("resample", image);
    const Dims old_dims = image.dims(); // a copy: the image is replaced below
    Dims dims{};
    Vec3 ratio{}, first_centre{};
    double count = 1;
    for (int a = 0; a < 3; ++a) {
        const double s = options.spacing_mm[a];
        if (!std::isfinite(s) || s <= 0)
            throw InputError(concat("resample: spacing ", format_mm(s), " mm along axis ", a,
                                    "; it must be a positive number (e.g. --spacing-mm 1 or 1,1,1.5)"));
        ratio[a] = s / image.spacing_mm()[a];
        const double extent = static_cast<double>(old_dims[a]) / ratio[a];
        dims[a] = static_cast<std::size_t>(std::max(1.0, std::round(std::min(extent, 4e9))));
        count *= static_cast<double>(dims[a]);
        first_centre[a] = 0.5 * ratio[a] - 0.5;
    }
    if (count > 2147483648.0)
        throw InputError(concat("resample: ", format_mm(options.spacing_mm[0]), " mm voxels would make ", count,
                                " voxels (over 2^31); choose a coarser spacing"));
    const AxisOverlaps x = axis_overlaps(old_dims[0], dims[0], ratio[0]);
    const AxisOverlaps y = axis_overlaps(old_dims[1], dims[1], ratio[1]);
    const AxisOverlaps z = axis_overlaps(old_dims[2], dims[2], ratio[2]);
    LabelImage result(dims, options.spacing_mm, image.index_to_world(first_centre), image.direction());
    ProgressTicker ticker(progress, "resample", dims[2]);
    std::vector<std::pair<Label, double>> weights;
    for (std::size_t k = 0; k < dims[2]; ++k, ticker.step())
        for (std::size_t j = 0; j < dims[1]; ++j)
            for (std::size_t i = 0; i < dims[0]; ++i) {
                if (options.method == ResampleMethod::nearest) {
                    result.at(i, j, k) = image.at(x.nearest[i], y.nearest[j], z.nearest[k]);
                    continue;
                }
                result.at(i, j, k) = majority(image, x.cells[i], y.cells[j], z.cells[k], weights, background);
            }
    result.names() = image.names();
    image = std::move(result);
    report.detail = concat(options.method == ResampleMethod::majority ? "majority" : "nearest", " to ",
                           format_mm(options.spacing_mm[0]), " x ", format_mm(options.spacing_mm[1]), " x ",
                           format_mm(options.spacing_mm[2]), " mm: ", old_dims[0], "x", old_dims[1], "x", old_dims[2],
                           " -> ", dims[0], "x", dims[1], "x", dims[2], " voxels");
    finish_report(report, image);
    return report;
}

} // namespace tissuemesh::image

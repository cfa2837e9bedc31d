#include "surface/thin_first_priority.h"

#include <algorithm>
#include <vector>

#include "core/error.h"

namespace tissuemesh::surface {

std::map<Label, int> thin_first_priority(const LabelImage& image, Label background)
{
    if (image.empty()) throw InputError("thin-first priority: the image has no voxels; give a non-empty image");
    std::vector<double> volume(std::size_t{1} << 16, 0), surface(std::size_t{1} << 16, 0);
    const Dims& d = image.dims();
    const auto face = [&](Label a, Label b) {
        if (a == b) return;
        surface[a] += 1;
        surface[b] += 1;
    };
    for (std::size_t k = 0; k < d[2]; ++k)
        for (std::size_t j = 0; j < d[1]; ++j)
            for (std::size_t i = 0; i < d[0]; ++i) {
                const Label label = image.at(i, j, k);
                volume[label] += 1;
                face(label, i + 1 < d[0] ? image.at(i + 1, j, k) : background);
                face(label, j + 1 < d[1] ? image.at(i, j + 1, k) : background);
                face(label, k + 1 < d[2] ? image.at(i, j, k + 1) : background);
                if (i == 0) face(label, background);
                if (j == 0) face(label, background);
                if (k == 0) face(label, background);
            }
    std::vector<std::pair<double, Label>> thickness;
    for (std::size_t l = 0; l < volume.size(); ++l)
        if (volume[l] > 0 && l != background)
            thickness.emplace_back(2 * volume[l] / std::max(surface[l], 1.0), static_cast<Label>(l));
    std::sort(thickness.begin(), thickness.end());
    std::map<Label, int> priority;
    const int count = static_cast<int>(thickness.size());
    for (int rank = 0; rank < count; ++rank) priority[thickness[static_cast<std::size_t>(rank)].second] = count - rank;
    return priority;
}

} // namespace tissuemesh::surface

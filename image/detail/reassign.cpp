#include "image/detail/reassign.h"

#include <algorithm>
#include <limits>

namespace tissuemesh::image::detail {
namespace {

constexpr std::uint32_t not_selected = std::numeric_limits<std::uint32_t>::max();

/// slot[c] = position of component c in `selected`, or not_selected.
std::vector<std::uint32_t> slots(const Components& components, const std::vector<std::uint32_t>& selected)
{
    std::vector<std::uint32_t> slot(components.count(), not_selected);
    for (std::size_t n = 0; n < selected.size(); ++n) slot[selected[n]] = static_cast<std::uint32_t>(n);
    return slot;
}

} // namespace

std::vector<std::map<Label, std::size_t>> surrounding_labels(const LabelImage& image, const Components& components,
                                                             const std::vector<std::uint32_t>& selected,
                                                             bool skip_selected)
{
    std::vector<std::map<Label, std::size_t>> histograms(selected.size());
    const std::vector<std::uint32_t> slot = slots(components, selected);
    const Dims& d = image.dims();
    const std::size_t stride[3] = {1, d[0], d[0] * d[1]};
    for (std::size_t k = 0; k < d[2]; ++k)
        for (std::size_t j = 0; j < d[1]; ++j)
            for (std::size_t i = 0; i < d[0]; ++i) {
                const std::size_t v = image.linear_index(i, j, k);
                const std::uint32_t c = components.component[v];
                if (slot[c] == not_selected) continue;
                const std::size_t index[3] = {i, j, k};
                const auto count = [&](std::size_t w) {
                    const std::uint32_t other = components.component[w];
                    if (other != c && !(skip_selected && slot[other] != not_selected))
                        ++histograms[slot[c]][image.labels()[w]];
                };
                for (int a = 0; a < 3; ++a) {
                    if (index[a] > 0) count(v - stride[a]);
                    if (index[a] + 1 < d[a]) count(v + stride[a]);
                }
            }
    return histograms;
}

Label most_common(const std::map<Label, std::size_t>& histogram, Label fallback)
{
    Label best = fallback;
    std::size_t best_count = 0;
    for (const auto& [label, count] : histogram)
        if (count > best_count) best = label, best_count = count; // ascending: ties keep the smaller
    return best;
}

std::size_t assign_components(LabelImage& image, const Components& components,
                              const std::vector<std::uint32_t>& selected, const std::vector<Label>& new_labels)
{
    const std::vector<std::uint32_t> slot = slots(components, selected);
    std::size_t changed = 0;
    auto& labels = image.labels();
    for (std::size_t v = 0; v < labels.size(); ++v) {
        const std::uint32_t s = slot[components.component[v]];
        if (s == not_selected || labels[v] == new_labels[s]) continue;
        labels[v] = new_labels[s];
        ++changed;
    }
    return changed;
}

std::size_t absorb_components(LabelImage& image, const Components& components,
                              const std::vector<std::uint32_t>& selected)
{
    const auto staying = surrounding_labels(image, components, selected, true);
    std::vector<std::map<Label, std::size_t>> all;
    if (std::any_of(staying.begin(), staying.end(), [](const auto& h) { return h.empty(); }))
        all = surrounding_labels(image, components, selected, false);
    std::vector<Label> targets(selected.size());
    for (std::size_t n = 0; n < selected.size(); ++n)
        targets[n] =
            most_common(staying[n].empty() && !all.empty() ? all[n] : staying[n], components.label[selected[n]]);
    return assign_components(image, components, selected, targets);
}

} // namespace tissuemesh::image::detail

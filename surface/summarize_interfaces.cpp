#include "surface/summarize_interfaces.h"

#include <algorithm>
#include <array>
#include <set>
#include <unordered_map>
#include <utility>

namespace tissuemesh::surface {
namespace {

/// Up to 4 distinct labels seen around an edge (4 is enough to know "3 or more").
struct EdgeLabels {
    std::array<Label, 4> labels{};
    int count = 0;
    void add(Label label)
    {
        if (count == 4 || std::find(labels.begin(), labels.begin() + count, label) != labels.begin() + count) return;
        labels[static_cast<std::size_t>(count++)] = label;
    }
};

} // namespace

InterfaceSummary summarize_interfaces(const InterfaceComplex& complex)
{
    InterfaceSummary summary;
    std::set<std::pair<Label, Label>> pairs;
    std::unordered_map<std::uint64_t, EdgeLabels> edges;
    edges.reserve(complex.triangles.size() * 2);
    for (std::size_t t = 0; t < complex.triangles.size(); ++t) {
        const LabelPair side = complex.sides[t];
        ++summary.tissues[side.from].triangles;
        ++summary.tissues[side.to].triangles;
        pairs.insert(std::minmax(side.from, side.to));
        for (int e = 0; e < 3; ++e) {
            const std::uint32_t a = complex.triangles[t][static_cast<std::size_t>(e)];
            const std::uint32_t b = complex.triangles[t][static_cast<std::size_t>((e + 1) % 3)];
            EdgeLabels& labels = edges[std::uint64_t{std::min(a, b)} << 32 | std::max(a, b)];
            labels.add(side.from);
            labels.add(side.to);
        }
    }
    summary.patches = pairs.size();
    for (const auto& [key, labels] : edges) {
        if (labels.count < 3) continue;
        ++summary.junction_edges;
        for (int l = 0; l < labels.count; ++l) ++summary.tissues[labels.labels[static_cast<std::size_t>(l)]].junction_edges;
    }
    return summary;
}

} // namespace tissuemesh::surface

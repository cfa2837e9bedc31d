#include "surface/summarize_interfaces.h"

#include <algorithm>
#include <array>
#include <set>
#include <vector>
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
    // Edges bucketed by their lower vertex (compressed rows): (other vertex, triangle) per use.
    const std::size_t n = complex.vertices.size();
    std::vector<std::size_t> start(n + 1, 0);
    for (const Triangle& tri : complex.triangles)
        for (int e = 0; e < 3; ++e) ++start[std::min(tri[static_cast<std::size_t>(e)], tri[static_cast<std::size_t>((e + 1) % 3)]) + 1];
    for (std::size_t v = 0; v < n; ++v) start[v + 1] += start[v];
    std::vector<std::pair<std::uint32_t, std::uint32_t>> uses(start[n]);
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t t = 0; t < complex.triangles.size(); ++t) {
        const LabelPair side = complex.sides[t];
        ++summary.tissues[side.from].triangles;
        ++summary.tissues[side.to].triangles;
        pairs.insert(std::minmax(side.from, side.to));
        const Triangle& tri = complex.triangles[t];
        for (int e = 0; e < 3; ++e) {
            const auto [a, b] = std::minmax(tri[static_cast<std::size_t>(e)], tri[static_cast<std::size_t>((e + 1) % 3)]);
            uses[fill[a]++] = {b, static_cast<std::uint32_t>(t)};
        }
    }
    summary.patches = pairs.size();
    for (std::size_t v = 0; v < n; ++v) {
        const auto first = uses.begin() + static_cast<std::ptrdiff_t>(start[v]);
        const auto last = uses.begin() + static_cast<std::ptrdiff_t>(start[v + 1]);
        std::sort(first, last);
        for (auto run = first; run != last;) {
            EdgeLabels labels;
            auto next = run;
            for (; next != last && next->first == run->first; ++next) {
                labels.add(complex.sides[next->second].from);
                labels.add(complex.sides[next->second].to);
            }
            run = next;
            if (labels.count < 3) continue;
            ++summary.junction_edges;
            for (int l = 0; l < labels.count; ++l) ++summary.tissues[labels.labels[static_cast<std::size_t>(l)]].junction_edges;
        }
    }
    return summary;
}

} // namespace tissuemesh::surface

#include "surface/detail/snake_resolution.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <optional>
#include <utility>
#include <vector>

namespace tissuemesh::surface::detail {
namespace {

using Edge = std::pair<std::uint32_t, std::uint32_t>;

std::vector<Edge> alive_edges(const ComplexEditor& editor)
{
    std::vector<Edge> edges;
    for (std::uint32_t t = 0; t < editor.triangle_slots(); ++t) {
        if (!editor.triangle_alive(t)) continue;
        const Triangle& tri = editor.triangle(t);
        for (int e = 0; e < 3; ++e) {
            const std::uint32_t a = tri[static_cast<std::size_t>(e)], b = tri[static_cast<std::size_t>((e + 1) % 3)];
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    return edges;
}

bool edge_alive(const ComplexEditor& editor, const Edge& e)
{
    return editor.vertex_alive(e.first) && editor.vertex_alive(e.second) &&
           editor.edge_multiplicity(e.first, e.second) > 0;
}

int valence(const ComplexEditor& editor, std::uint32_t v) { return static_cast<int>(editor.neighbours(v).size()); }

} // namespace

ResolutionCounts adapt_resolution(ComplexEditor& editor, const std::function<double(std::uint32_t)>& target_mm)
{
    ResolutionCounts counts;
    const auto target = [&](const Edge& e) { return std::min(target_mm(e.first), target_mm(e.second)); };
    const auto length = [&](const Edge& e) { return distance(editor.position(e.first), editor.position(e.second)); };

    std::vector<Edge> edges = alive_edges(editor);
    // Longest first, so that a split never starts from an edge a neighbouring split just halved.
    std::sort(edges.begin(), edges.end(), [&](const Edge& x, const Edge& y) { return length(x) > length(y); });
    for (const Edge& e : edges) {
        if (!edge_alive(editor, e) || length(e) <= 4.0 / 3.0 * target(e)) continue;
        if (editor.try_split(e.first, e.second, 0.5 * (editor.position(e.first) + editor.position(e.second))))
            ++counts.splits;
    }

    edges = alive_edges(editor);
    std::sort(edges.begin(), edges.end(), [&](const Edge& x, const Edge& y) { return length(x) < length(y); });
    for (const Edge& e : edges) {
        if (!edge_alive(editor, e)) continue;
        const double limit = target(e);
        if (length(e) >= 0.8 * limit) continue;
        // v disappears into w: every edge of v becomes an edge of w.
        const std::uint32_t v = e.first, w = e.second;
        bool too_long = false;
        for (const std::uint32_t u : editor.neighbours(v))
            if (distance(editor.position(u), editor.position(w)) > 4.0 / 3.0 * limit) too_long = true;
        if (!too_long && editor.try_collapse(v, w)) ++counts.collapses;
    }

    for (const Edge& e : alive_edges(editor)) {
        if (!edge_alive(editor, e)) continue;
        const std::optional<std::array<std::uint32_t, 2>> opposite = editor.opposite_vertices(e.first, e.second);
        if (!opposite) continue;
        const auto [a, b] = *opposite;
        if (editor.edge_multiplicity(a, b) > 0) continue;
        const int v = valence(editor, e.first), w = valence(editor, e.second);
        const int va = valence(editor, a), vb = valence(editor, b);
        const int before = std::abs(v - 6) + std::abs(w - 6) + std::abs(va - 6) + std::abs(vb - 6);
        const int after = std::abs(v - 7) + std::abs(w - 7) + std::abs(va - 5) + std::abs(vb - 5);
        if (after < before && editor.try_flip(e.first, e.second)) ++counts.flips;
    }
    return counts;
}

} // namespace tissuemesh::surface::detail

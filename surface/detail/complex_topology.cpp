// ComplexEditor's questions about connectivity: neighbours, edge multiplicities, vertex kinds and the link
// condition of a collapse (the edits are in complex_editor.cpp).
#include <algorithm>

#include "surface/detail/complex_editor.h"
#include "surface/detail/edit_rules.h"

namespace tissuemesh::surface::detail {

std::vector<std::uint32_t> ComplexEditor::neighbours(std::uint32_t v) const
{
    std::vector<std::uint32_t> result;
    for (const std::uint32_t t : stars_[v])
        for (const std::uint32_t u : triangles_[t])
            if (u != v) result.push_back(u);
    std::sort(result.begin(), result.end());
    result.erase(std::unique(result.begin(), result.end()), result.end());
    return result;
}

void ComplexEditor::ring(std::uint32_t v, std::vector<RingEntry>& out) const
{
    out.clear();
    // A star has a few dozen entries at most: a linear search beats sorting.
    for (const std::uint32_t t : stars_[v])
        for (const std::uint32_t u : triangles_[t]) {
            if (u == v) continue;
            auto it = out.begin();
            while (it != out.end() && it->vertex != u) ++it;
            if (it == out.end()) out.push_back({u, 1});
            else ++it->triangles;
        }
}

std::size_t ComplexEditor::edge_multiplicity(std::uint32_t v, std::uint32_t w) const
{
    std::size_t count = 0;
    for (const std::uint32_t t : stars_[v]) count += contains(triangles_[t], w) ? 1 : 0;
    return count;
}

std::vector<std::uint32_t> ComplexEditor::curve_neighbours(std::uint32_t v) const
{
    std::vector<std::uint32_t> result;
    for (const std::uint32_t u : neighbours(v))
        if (edge_multiplicity(v, u) >= 3) result.push_back(u);
    return result;
}

/// patch: one closed fan of one patch (every edge at v shared by two triangles of that patch);
/// curve: exactly two junction edges, every other edge shared by two triangles; corner: anything else.
VertexKind ComplexEditor::classify(std::uint32_t v) const
{
    const auto& star = stars_[v];
    if (star.empty()) return VertexKind::corner;
    thread_local std::vector<RingEntry> around;
    ring(v, around);
    std::size_t junction = 0;
    for (const RingEntry& e : around) {
        if (e.triangles >= 3) ++junction;
        else if (e.triangles != 2) return VertexKind::corner;
    }
    if (junction == 2) return VertexKind::curve;
    if (junction != 0) return VertexKind::corner;
    const LabelPair first = sides_[star.front()];
    for (const std::uint32_t t : star)
        if (!(sides_[t] == first)) return VertexKind::corner;
    // A single fan: as many distinct neighbours as triangles (two fans touching at v would share none).
    return around.size() == star.size() ? VertexKind::patch : VertexKind::corner;
}

void ComplexEditor::update_kinds(std::uint32_t v, const std::vector<std::uint32_t>* others)
{
    reclassified_.clear();
    const auto update = [&](std::uint32_t u) {
        const VertexKind kind = classify(u);
        if (kind != kinds_[u]) reclassified_.push_back(u);
        kinds_[u] = kind;
    };
    update(v);
    if (others) {
        for (const std::uint32_t u : *others) update(u);
        return;
    }
    thread_local std::vector<RingEntry> around;
    ring(v, around);
    for (const RingEntry& e : around) update(e.vertex);
}

/// Lk(v) n Lk(w) = Lk(vw): the common neighbours are exactly the third vertices of triangles on vw, and
/// no edge ab has both triangles vab and wab. Plus the interface rule that merged edges keep their
/// multiplicity (no two junction edges fuse).
bool ComplexEditor::link_condition(std::uint32_t v, std::uint32_t w) const
{
    thread_local std::vector<RingEntry> nv, nw;
    thread_local std::vector<std::uint32_t> apexes;
    ring(v, nv);
    ring(w, nw);
    apexes.clear();
    for (const std::uint32_t t : stars_[v])
        if (contains(triangles_[t], w))
            for (const std::uint32_t u : triangles_[t])
                if (u != v && u != w && std::find(apexes.begin(), apexes.end(), u) == apexes.end()) apexes.push_back(u);
    // The common neighbours must be the apexes (each list holds distinct vertices); meanwhile note whether
    // some common neighbour's edges to v and w are not both ordinary.
    std::size_t common = 0;
    bool fused = false;
    for (const RingEntry& a : nv)
        for (const RingEntry& b : nw)
            if (a.vertex == b.vertex) {
                if (std::find(apexes.begin(), apexes.end(), a.vertex) == apexes.end()) return false;
                ++common;
                fused = fused || std::min(a.triangles, b.triangles) != 2;
            }
    if (common != apexes.size()) return false;
    // Edges vx and wx merge; at most one of them may be a junction edge, or two junction curves would
    // fuse into an edge where a tissue touches itself (x runs over the apexes, now the common neighbours).
    if (fused) return false;
    for (const std::uint32_t t : stars_[v]) {
        const Triangle r = starting_at(triangles_[t], v);
        if (r[1] == w || r[2] == w) continue;
        for (const std::uint32_t s : stars_[w])
            if (contains(triangles_[s], r[1]) && contains(triangles_[s], r[2])) return false;
    }
    return true;
}

std::vector<Label> tissues_around(const ComplexEditor& editor, std::uint32_t v)
{
    std::vector<Label> tissues;
    for (const std::uint32_t t : editor.star(v)) tissues.insert(tissues.end(), {editor.side(t).from, editor.side(t).to});
    std::sort(tissues.begin(), tissues.end());
    tissues.erase(std::unique(tissues.begin(), tissues.end()), tissues.end());
    return tissues;
}

} // namespace tissuemesh::surface::detail

// ComplexEditor's question about connectivity of its own: the link condition of a collapse (the edits are
// in complex_editor.cpp; neighbours, multiplicities and vertex kinds in editable_complex.cpp).
#include <algorithm>

#include "surface/detail/complex_editor.h"
#include "surface/detail/edit_rules.h"

namespace tissuemesh::surface::detail {

/// Lk(v) n Lk(w) = Lk(vw): the common neighbours are exactly the third vertices of triangles on vw, and
/// no edge ab has both triangles vab and wab. Plus the interface rule that merged edges keep their
/// multiplicity (no two junction edges fuse).
bool ComplexEditor::link_condition(std::uint32_t v, std::uint32_t w) const
{
    std::vector<RingEntry>& nv = link_ring_v_;
    std::vector<RingEntry>& nw = link_ring_w_;
    std::vector<std::uint32_t>& apexes = link_apexes_;
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
    for (const std::uint32_t t : editor.star(v))
        tissues.insert(tissues.end(), {editor.side(t).from, editor.side(t).to});
    std::sort(tissues.begin(), tissues.end());
    tissues.erase(std::unique(tissues.begin(), tissues.end()), tissues.end());
    return tissues;
}

} // namespace tissuemesh::surface::detail

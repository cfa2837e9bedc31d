#include "surface/detail/editable_complex.h"

#include <algorithm>

namespace tissuemesh::surface::detail {

EditableComplex::EditableComplex(InterfaceComplex&& complex)
    : background_(complex.background), names_(std::move(complex.names)), positions_(std::move(complex.vertices)),
      triangles_(std::move(complex.triangles)), sides_(std::move(complex.sides)), alive_(triangles_.size(), 1),
      stars_(positions_.size()), kinds_(positions_.size(), VertexKind::corner), alive_count_(triangles_.size())
{
    for (std::uint32_t t = 0; t < triangles_.size(); ++t)
        for (const std::uint32_t v : triangles_[t]) stars_[v].push_back(t);
}

double EditableComplex::mean_edge_length() const
{
    double sum = 0;
    for (std::uint32_t t = 0; t < triangles_.size(); ++t)
        if (alive_[t]) sum += distance(positions_[triangles_[t][0]], positions_[triangles_[t][1]]);
    return alive_count_ == 0 ? 1.0 : sum / static_cast<double>(alive_count_);
}

void EditableComplex::ring(std::uint32_t v, std::vector<RingEntry>& out) const
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

std::vector<std::uint32_t> EditableComplex::neighbours(std::uint32_t v) const
{
    std::vector<std::uint32_t> result;
    for (const std::uint32_t t : stars_[v])
        for (const std::uint32_t u : triangles_[t])
            if (u != v) result.push_back(u);
    std::sort(result.begin(), result.end());
    result.erase(std::unique(result.begin(), result.end()), result.end());
    return result;
}

std::vector<std::uint32_t> EditableComplex::curve_neighbours(std::uint32_t v) const
{
    std::vector<std::uint32_t> result;
    for (const std::uint32_t u : neighbours(v))
        if (edge_multiplicity(v, u) >= 3) result.push_back(u);
    return result;
}

std::uint32_t EditableComplex::edge_multiplicity(std::uint32_t v, std::uint32_t w) const
{
    std::uint32_t count = 0;
    for (const std::uint32_t t : stars_[v]) {
        const Triangle& tri = triangles_[t];
        count += tri[0] == w || tri[1] == w || tri[2] == w;
    }
    return count;
}

std::optional<std::array<std::uint32_t, 2>> EditableComplex::opposite_vertices(std::uint32_t v, std::uint32_t w) const
{
    std::array<std::uint32_t, 2> found{};
    std::size_t count = 0;
    for (const std::uint32_t t : stars_[v]) {
        const Triangle& tri = triangles_[t];
        if (tri[0] != w && tri[1] != w && tri[2] != w) continue;
        for (const std::uint32_t u : tri)
            if (u != v && u != w) {
                if (count < 2) found[count] = u;
                ++count;
            }
    }
    if (count != 2) return std::nullopt;
    return found;
}

InterfaceComplex EditableComplex::snapshot() const
{
    InterfaceComplex out;
    out.background = background_;
    out.names = names_;
    out.vertices = positions_;
    for (std::uint32_t t = 0; t < triangles_.size(); ++t)
        if (alive_[t]) out.add_triangle(triangles_[t], sides_[t]);
    return out;
}

VertexKind EditableComplex::classify(std::uint32_t v) const
{
    const auto& star = stars_[v];
    if (star.empty()) return VertexKind::corner;
    ring(v, classify_ring_);
    std::size_t junction = 0;
    for (const RingEntry& e : classify_ring_) {
        if (e.triangles >= 3) ++junction;
        else if (e.triangles != 2) return VertexKind::corner;
    }
    if (junction == 2) return VertexKind::curve;
    if (junction != 0) return VertexKind::corner;
    const LabelPair first = sides_[star.front()];
    for (const std::uint32_t t : star)
        if (!(sides_[t] == first)) return VertexKind::corner;
    // A single fan: as many distinct neighbours as triangles (two fans touching at v would share none).
    return classify_ring_.size() == star.size() ? VertexKind::patch : VertexKind::corner;
}

void EditableComplex::classify_all()
{
    for (std::uint32_t v = 0; v < positions_.size(); ++v) kinds_[v] = classify(v);
}

void EditableComplex::reclassify(std::uint32_t v, const std::vector<std::uint32_t>* others)
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
    ring(v, reclassify_ring_);
    for (const RingEntry& e : reclassify_ring_) update(e.vertex);
}

} // namespace tissuemesh::surface::detail

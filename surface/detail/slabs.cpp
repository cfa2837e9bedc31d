#include "surface/detail/slabs.h"

#include <algorithm>
#include <exception>
#include <limits>

namespace tissuemesh::surface::detail {

std::pair<double, double> span(const InterfaceComplex& complex, std::uint32_t t, int axis)
{
    const Triangle& tri = complex.triangles[t];
    const double a = complex.vertices[tri[0]][axis], b = complex.vertices[tri[1]][axis],
                 c = complex.vertices[tri[2]][axis];
    return {std::min({a, b, c}), std::max({a, b, c})};
}

std::vector<Slab> cut_into_slabs(const InterfaceComplex& complex, std::size_t count)
{
    constexpr double infinity = std::numeric_limits<double>::infinity();
    Vec3 low{infinity, infinity, infinity}, high{-infinity, -infinity, -infinity};
    for (const Triangle& tri : complex.triangles)
        for (const std::uint32_t v : tri)
            for (int a = 0; a < 3; ++a) {
                low[a] = std::min(low[a], complex.vertices[v][a]);
                high[a] = std::max(high[a], complex.vertices[v][a]);
            }
    int axis = 0;
    for (int a = 1; a < 3; ++a)
        if (high[a] - low[a] > high[axis] - low[axis]) axis = a;
    std::vector<double> starts(complex.triangles.size());
    for (std::uint32_t t = 0; t < starts.size(); ++t) starts[t] = span(complex, t, axis).first;
    std::sort(starts.begin(), starts.end());
    std::vector<Slab> slabs;
    double from = -infinity;
    for (std::size_t k = 1; k <= count; ++k) {
        const double to = k == count || starts.empty() ? infinity : starts[k * starts.size() / count];
        if (to > from) slabs.push_back({axis, from, to}); // equal cuts (many equal starts) merge
        from = std::max(from, to);
    }
    if (slabs.empty() || slabs.back().high != infinity) slabs.push_back({axis, from, infinity});
    return slabs;
}

std::vector<Slab> slabs_between(const std::vector<Slab>& slabs)
{
    std::vector<Slab> between;
    if (slabs.size() < 3) return between;
    const int axis = slabs.front().axis;
    double from = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 1; k + 1 < slabs.size(); ++k) {
        const double to = 0.5 * (slabs[k].low + slabs[k].high);
        between.push_back({axis, from, to});
        from = to;
    }
    between.push_back({axis, from, std::numeric_limits<double>::infinity()});
    return between;
}

SlabPiece slab_piece(const InterfaceComplex& complex, const Slab& slab)
{
    SlabPiece piece;
    piece.complex.names = complex.names;
    piece.complex.background = complex.background;
    constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> local(complex.vertices.size(), none);
    for (std::uint32_t t = 0; t < complex.triangles.size(); ++t) {
        const auto [from, to] = span(complex, t, slab.axis);
        if (to < slab.low || from > slab.high) continue;
        Triangle tri = complex.triangles[t];
        for (std::uint32_t& v : tri) {
            if (local[v] == none) {
                local[v] = static_cast<std::uint32_t>(piece.from_vertex.size());
                piece.from_vertex.push_back(v);
                piece.complex.vertices.push_back(complex.vertices[v]);
            }
            v = local[v];
        }
        piece.complex.add_triangle(tri, complex.sides[t]);
        piece.from_triangle.push_back(t);
    }
    return piece;
}

void edit_slabs(const InterfaceComplex& complex, const std::vector<Slab>& slabs, const std::vector<char>& run,
                const std::function<void(std::size_t, SlabPiece&)>& edit,
                const std::function<void(std::size_t)>& finished)
{
    std::exception_ptr failure;
    std::size_t done = 0;
#pragma omp parallel for schedule(dynamic, 1)
    for (std::size_t k = 0; k < slabs.size(); ++k) {
        if (!run.empty() && !run[k]) continue;
        try {
            SlabPiece piece = slab_piece(complex, slabs[k]);
            edit(k, piece);
        } catch (...) {
#pragma omp critical(slab_failure)
            if (!failure) failure = std::current_exception();
        }
        if (finished) {
#pragma omp critical(slab_finished)
            finished(++done);
        }
    }
    if (failure) std::rethrow_exception(failure);
}

InterfaceComplex merge_slabs(const InterfaceComplex& whole, const std::vector<EditedSlab>& slabs)
{
    InterfaceComplex merged;
    merged.names = whole.names;
    merged.background = whole.background;
    merged.vertices = whole.vertices;
    for (const EditedSlab& slab : slabs) {
        const InterfaceComplex& source = slab.edited ? *slab.edited : whole;
        // New vertices of the piece go after the whole's (a vertex a piece moved or made lies inside its
        // fence, so no other piece holds it).
        std::vector<std::uint32_t> added(slab.edited ? source.vertices.size() : 0,
                                         std::numeric_limits<std::uint32_t>::max());
        for (std::uint32_t t = 0; t < source.triangles.size(); ++t) {
            if (!slab.slab.owns(span(source, t, slab.slab.axis).first)) continue;
            Triangle tri = source.triangles[t];
            if (slab.edited)
                for (std::uint32_t& v : tri) {
                    if (v < slab.from_vertex.size()) {
                        merged.vertices[slab.from_vertex[v]] = source.vertices[v];
                        v = slab.from_vertex[v];
                        continue;
                    }
                    if (added[v] == std::numeric_limits<std::uint32_t>::max()) {
                        added[v] = static_cast<std::uint32_t>(merged.vertices.size());
                        merged.vertices.push_back(source.vertices[v]);
                    }
                    v = added[v];
                }
            merged.add_triangle(tri, source.sides[t]);
        }
    }
    // Drop the vertices no triangle uses any more, keeping the order.
    constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> index(merged.vertices.size(), none);
    for (const Triangle& tri : merged.triangles)
        for (const std::uint32_t v : tri) index[v] = 0;
    std::vector<Vec3> kept;
    for (std::uint32_t v = 0; v < merged.vertices.size(); ++v)
        if (index[v] != none) index[v] = static_cast<std::uint32_t>(kept.size()), kept.push_back(merged.vertices[v]);
    merged.vertices = std::move(kept);
    for (Triangle& tri : merged.triangles)
        for (std::uint32_t& v : tri) v = index[v];
    return merged;
}

} // namespace tissuemesh::surface::detail

#include "surface/tissue_surface.h"

#include <limits>

#include "core/error.h"

namespace tissuemesh::surface {

InterfaceComplex tissue_surface(const InterfaceComplex& complex, Label tissue)
{
    constexpr std::uint32_t unused = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> renumber(complex.vertices.size(), unused);
    InterfaceComplex surface;
    surface.names = complex.names;
    surface.background = complex.background;
    for (std::size_t t = 0; t < complex.triangles.size(); ++t) {
        const LabelPair pair = complex.sides[t];
        if (pair.from != tissue && pair.to != tissue) continue;
        Triangle triangle = complex.triangles[t];
        // Outward: the tissue must be behind the triangle, i.e. be its `from` side.
        if (pair.to == tissue) std::swap(triangle[1], triangle[2]);
        for (std::uint32_t& v : triangle) {
            if (renumber[v] == unused) {
                renumber[v] = static_cast<std::uint32_t>(surface.vertices.size());
                surface.vertices.push_back(complex.vertices[v]);
            }
            v = renumber[v];
        }
        surface.add_triangle(triangle, {tissue, pair.from == tissue ? pair.to : pair.from});
    }
    if (surface.triangles.empty())
        throw InputError(concat("tissue_surface: no triangle borders tissue ", tissue,
                                "; check the tissue number against the complex's labels"));
    return surface;
}

} // namespace tissuemesh::surface

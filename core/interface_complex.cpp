#include "core/interface_complex.h"

#include "core/error.h"

namespace tissuemesh {

void validate_indices(const InterfaceComplex& complex, const std::string& what)
{
    if (complex.sides.size() != complex.triangles.size())
        throw InputError(concat(what, ": ", complex.triangles.size(), " triangles but ", complex.sides.size(),
                                " label pairs; every triangle needs the two tissues it separates"));
    for (std::size_t v = 0; v < complex.vertices.size(); ++v)
        if (!is_finite(complex.vertices[v]))
            throw InputError(concat(what, ": vertex ", v, " has a non-finite coordinate; the surface file is corrupt"));
    for (std::size_t t = 0; t < complex.triangles.size(); ++t) {
        const Triangle& tri = complex.triangles[t];
        for (const std::uint32_t v : tri)
            if (v >= complex.vertices.size())
                throw InputError(concat(what, ": triangle ", t, " refers to vertex ", v, " but there are only ",
                                        complex.vertices.size(), " vertices; the surface file is corrupt"));
        if (complex.sides[t].from == complex.sides[t].to)
            throw InputError(concat(what, ": triangle ", t, " separates tissue ", complex.sides[t].from,
                                    " from itself; every interface triangle separates two different tissues"));
    }
}

} // namespace tissuemesh

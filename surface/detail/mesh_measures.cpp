#include "surface/detail/mesh_measures.h"

namespace tissuemesh::surface::detail {

double mean_edge_length(const InterfaceComplex& complex)
{
    double sum = 0;
    for (const Triangle& t : complex.triangles) sum += distance(complex.vertices[t[0]], complex.vertices[t[1]]);
    return complex.triangles.empty() ? 1.0 : sum / static_cast<double>(complex.triangles.size());
}

} // namespace tissuemesh::surface::detail

#include "surface/detail/mesh_measures.h"

#include <algorithm>
#include <cmath>

namespace tissuemesh::surface::detail {

double mean_edge_length(const InterfaceComplex& complex)
{
    double sum = 0;
    for (const Triangle& t : complex.triangles) sum += distance(complex.vertices[t[0]], complex.vertices[t[1]]);
    return complex.triangles.empty() ? 1.0 : sum / static_cast<double>(complex.triangles.size());
}

double smallest_angle_deg(const TriangleCorners& p)
{
    constexpr double degrees = 180.0 / 3.14159265358979323846;
    double smallest = 180;
    for (int k = 0; k < 3; ++k) {
        const Vec3 u = p[(k + 1) % 3] - p[k];
        const Vec3 w = p[(k + 2) % 3] - p[k];
        smallest = std::min(smallest, std::atan2(norm(cross(u, w)), dot(u, w)) * degrees);
    }
    return smallest;
}

} // namespace tissuemesh::surface::detail

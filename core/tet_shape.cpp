#include "core/tet_shape.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace tissuemesh {

std::pair<double, double> dihedral_range_deg(const TetMesh& mesh, std::size_t t)
{
    constexpr double pi = 3.14159265358979323846;
    const Tet& tet = mesh.tets[t];
    std::array<Vec3, 4> p;
    for (int c = 0; c < 4; ++c) p[c] = mesh.vertices[tet[c]];
    // Dihedral angle at the edge two faces share, from their outward unit normals: 180 degrees less the angle
    // between the normals, so it grows with their (clamped) dot product.
    std::array<Vec3, 4> normals;
    for (int f = 0; f < 4; ++f) {
        const Vec3& a = p[tet_faces[f][0]];
        Vec3 n = cross(p[tet_faces[f][1]] - a, p[tet_faces[f][2]] - a);
        const double length = norm(n);
        normals[f] = length > 0 ? (1.0 / length) * n : Vec3{0, 0, 0};
    }
    double low = 1, high = -1;
    for (int f = 0; f < 4; ++f)
        for (int g = f + 1; g < 4; ++g) {
            const double d = std::clamp(dot(normals[f], normals[g]), -1.0, 1.0);
            low = std::min(low, d), high = std::max(high, d);
        }
    const auto angle = [&](double d) { return 180.0 - std::acos(d) * 180.0 / pi; };
    return {angle(low), angle(high)};
}

TetShape tet_shape(const TetMesh& mesh, std::size_t t)
{
    const Tet& tet = mesh.tets[t];
    std::array<Vec3, 4> p;
    for (int c = 0; c < 4; ++c) p[c] = mesh.vertices[tet[c]];
    const auto [min_angle, max_angle] = dihedral_range_deg(mesh, t);
    double shortest = std::numeric_limits<double>::max();
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) shortest = std::min(shortest, distance(p[i], p[j]));
    // Circumcentre relative to p0: (|a|^2 (b x c) + |b|^2 (c x a) + |c|^2 (a x b)) / (2 a.(b x c)).
    const Vec3 a = p[1] - p[0], b = p[2] - p[0], c = p[3] - p[0];
    const double det = 2 * dot(a, cross(b, c));
    const Vec3 centre = (1.0 / det) * (dot(a, a) * cross(b, c) + dot(b, b) * cross(c, a) + dot(c, c) * cross(a, b));
    const double ratio = det != 0 && shortest > 0 ? norm(centre) / shortest : std::numeric_limits<double>::infinity();
    return {min_angle, max_angle, ratio};
}

} // namespace tissuemesh

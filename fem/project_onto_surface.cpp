#include "fem/project_onto_surface.h"

#include <cmath>
#include <cstdint>
#include <limits>

#include "core/error.h"
#include "fem/detail/nearest_on_triangle.h"

namespace tissuemesh::fem {

using detail::nearest_on_triangle;

std::vector<SurfacePoint> project_onto_surface(const TetMesh& mesh, const OuterBoundary& boundary,
                                               const std::vector<Vec3>& points_mm,
                                               const std::vector<std::string>& names, double max_distance_mm)
{
    if (boundary.faces.empty()) throw InputError("the mesh has no outer boundary face to put the electrodes on");
    std::vector<SurfacePoint> projected(points_mm.size());
    const auto count = static_cast<std::int64_t>(points_mm.size());
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t k = 0; k < count; ++k) {
        const Vec3& p = points_mm[static_cast<std::size_t>(k)];
        SurfacePoint& best = projected[static_cast<std::size_t>(k)];
        best.distance_mm = std::numeric_limits<double>::infinity();
        for (const Triangle& face : boundary.faces) {
            const Vec3 &a = mesh.vertices[face[0]], &b = mesh.vertices[face[1]], &c = mesh.vertices[face[2]];
            const std::array<double, 3> w = nearest_on_triangle(p, a, b, c);
            const Vec3 q = w[0] * a + w[1] * b + w[2] * c;
            const double d = distance(p, q);
            if (d < best.distance_mm) best = {face, w, q, d};
        }
    }
    for (std::size_t k = 0; k < projected.size(); ++k) {
        if (projected[k].distance_mm <= max_distance_mm) continue;
        const std::string name = k < names.size() && !names[k].empty() ? names[k] : concat("electrode ", k + 1);
        const Vec3& p = points_mm[k];
        throw InputError(concat(
            name, " at (", format_mm(p[0]), ", ", format_mm(p[1]), ", ", format_mm(p[2]), ") mm is ",
            format_mm(projected[k].distance_mm), " mm from the head's surface, more than ", format_mm(max_distance_mm),
            " mm; put it on the scalp (the mesh's coordinates, mm) or ", "raise --max-electrode-distance-mm"));
    }
    return projected;
}

} // namespace tissuemesh::fem

#include "fem/estimate_error.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/tet_adjacency.h"
#include "core/tet_shape.h"
#include "fem/assemble.h"
#include "fem/compute_fields.h"

namespace tissuemesh::fem {
namespace {

// 1/2 h_F |F| [J . n]_F^2 of the face (a, b, c) between two tets with currents j_in and j_out. The face's
// geometry is computed from its vertices in sorted order, so both tets get the same bytes.
double face_share(const TetMesh& mesh, Triangle face, const Vec3& j_in, const Vec3& j_out)
{
    std::sort(face.begin(), face.end());
    const Vec3 a = metres_per_mm * mesh.vertices[face[0]];
    const Vec3 b = metres_per_mm * mesh.vertices[face[1]];
    const Vec3 c = metres_per_mm * mesh.vertices[face[2]];
    const Vec3 normal = cross(b - a, c - a);
    const double area = 0.5 * norm(normal);
    const double h = std::max({distance(a, b), distance(b, c), distance(c, a)});
    const double jump = dot(j_in - j_out, (0.5 / area) * normal);
    return 0.5 * h * area * jump * jump;
}

} // namespace

std::vector<double> estimate_error(const TetMesh& mesh, const Conductivities& conductivities,
                                   const std::vector<double>& potential_v)
{
    const TetFields fields = compute_fields(mesh, conductivities, potential_v);
    const TetAdjacency adjacency(mesh.tets, mesh.vertex_count());
    const auto count = static_cast<std::int64_t>(mesh.tet_count());
    std::vector<double> indicator(mesh.tet_count(), 0.0);
    // Each tet sums its own faces (k = 0..3): every interior face is evaluated from both sides.
#pragma omp parallel for schedule(static)
    for (std::int64_t t = 0; t < count; ++t) {
        const auto tet_index = static_cast<std::size_t>(t);
        const Tet& tet = mesh.tets[tet_index];
        double squared = 0;
        for (int k = 0; k < 4; ++k) {
            const std::uint32_t other = adjacency.across(tet_index, k);
            if (other == no_tet) continue;
            const Triangle face{tet[tet_faces[k][0]], tet[tet_faces[k][1]], tet[tet_faces[k][2]]};
            squared += face_share(mesh, face, fields.current_a_per_m2[tet_index], fields.current_a_per_m2[other]);
        }
        indicator[tet_index] = std::sqrt(squared);
    }
    return indicator;
}

} // namespace tissuemesh::fem

#include "fem/estimate_error.h"

#include <algorithm>
#include <cmath>

#include "fem/assemble.h"
#include "fem/compute_fields.h"

namespace tissuemesh::fem {

std::vector<double> estimate_error(const TetMesh& mesh, const Conductivities& conductivities,
                                   const std::vector<double>& potential_v)
{
    const TetFields fields = compute_fields(mesh, conductivities, potential_v);
    struct FaceEntry {
        Triangle sorted;
        std::uint32_t tet;
    };
    // Face k of a tet is the one opposite its vertex k.
    std::vector<FaceEntry> faces;
    faces.reserve(4 * mesh.tet_count());
    for (std::uint32_t t = 0; t < mesh.tet_count(); ++t)
        for (int k = 0; k < 4; ++k) {
            Triangle face{};
            for (int i = 0, j = 0; i < 4; ++i)
                if (i != k) face[j++] = mesh.tets[t][i];
            std::sort(face.begin(), face.end());
            faces.push_back({face, t});
        }
    std::sort(faces.begin(), faces.end(), [](const FaceEntry& a, const FaceEntry& b) {
        return a.sorted != b.sorted ? a.sorted < b.sorted : a.tet < b.tet;
    });
    std::vector<double> squared(mesh.tet_count(), 0.0);
    for (std::size_t i = 0; i + 1 < faces.size(); ++i) {
        if (faces[i].sorted != faces[i + 1].sorted) continue;
        const Vec3 a = metres_per_mm * mesh.vertices[faces[i].sorted[0]];
        const Vec3 b = metres_per_mm * mesh.vertices[faces[i].sorted[1]];
        const Vec3 c = metres_per_mm * mesh.vertices[faces[i].sorted[2]];
        const Vec3 normal = cross(b - a, c - a);
        const double area = 0.5 * norm(normal);
        const double h = std::max({distance(a, b), distance(b, c), distance(c, a)});
        const double jump = dot(fields.current_a_per_m2[faces[i].tet] - fields.current_a_per_m2[faces[i + 1].tet],
                                (0.5 / area) * normal);
        const double share = 0.5 * h * area * jump * jump;
        squared[faces[i].tet] += share;
        squared[faces[i + 1].tet] += share;
        ++i;
    }
    for (double& value : squared) value = std::sqrt(value);
    return squared;
}

} // namespace tissuemesh::fem

#include "fem/assemble.h"

#include <vector>

#include "core/error.h"

namespace tissuemesh::fem {

P1Element p1_element(const TetMesh& mesh, std::size_t t)
{
    const Tet& tet = mesh.tets[t];
    const Vec3 origin = mesh.vertices[tet[0]];
    // Edge vectors in metres; the hat gradients are the rows of the inverse of [e1 e2 e3] (columns),
    // computed from cross products: grad(phi_k) = (e_i x e_j) / det for the cyclic pair (i, j).
    const Vec3 e1 = metres_per_mm * (mesh.vertices[tet[1]] - origin);
    const Vec3 e2 = metres_per_mm * (mesh.vertices[tet[2]] - origin);
    const Vec3 e3 = metres_per_mm * (mesh.vertices[tet[3]] - origin);
    const double det = dot(e1, cross(e2, e3));
    if (!(det > 0))
        throw InputError(concat("tet ", t, " has volume ", det / 6 * 1e9, " mm^3; P1 elements need positively ",
                                "oriented, non-degenerate tets: check the mesh with tm-check-mesh"));
    P1Element element;
    element.gradients[1] = (1 / det) * cross(e2, e3);
    element.gradients[2] = (1 / det) * cross(e3, e1);
    element.gradients[3] = (1 / det) * cross(e1, e2);
    element.gradients[0] = -1.0 * (element.gradients[1] + element.gradients[2] + element.gradients[3]);
    element.volume_m3 = det / 6;
    return element;
}

SparseMatrix assemble_stiffness(const TetMesh& mesh, const Conductivities& conductivities)
{
    validate_indices(mesh, "mesh");
    std::vector<Eigen::Triplet<double, int>> triplets;
    triplets.reserve(16 * mesh.tet_count());
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
        const Mat3& sigma = conductivities.of(mesh.tet_labels[t], t);
        const P1Element element = p1_element(mesh, t);
        for (int i = 0; i < 4; ++i) {
            const Vec3 flux = multiply(sigma, element.gradients[i]);
            for (int j = 0; j < 4; ++j)
                triplets.emplace_back(static_cast<int>(mesh.tets[t][i]), static_cast<int>(mesh.tets[t][j]),
                                      element.volume_m3 * dot(flux, element.gradients[j]));
        }
    }
    const auto n = static_cast<int>(mesh.vertex_count());
    SparseMatrix matrix(n, n);
    // setFromTriplets sums duplicates in triplet order: one thread, fixed order, same bytes every run.
    matrix.setFromTriplets(triplets.begin(), triplets.end());
    return matrix;
}

} // namespace tissuemesh::fem

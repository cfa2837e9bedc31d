#include "fem/compute_fields.h"

#include "core/error.h"
#include "fem/assemble.h"

namespace tissuemesh::fem {

TetFields compute_fields(const TetMesh& mesh, const Conductivities& conductivities,
                         const std::vector<double>& potential_v)
{
    if (potential_v.size() != mesh.vertex_count())
        throw InputError(concat("potential has ", potential_v.size(), " values but the mesh has ",
                                mesh.vertex_count(), " nodes; give one per node"));
    TetFields fields;
    fields.electric_v_per_m.reserve(mesh.tet_count());
    fields.current_a_per_m2.reserve(mesh.tet_count());
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
        const Mat3& sigma = conductivities.of(mesh.tet_labels[t], t);
        const P1Element element = p1_element(mesh, t);
        Vec3 field{0, 0, 0};
        for (int k = 0; k < 4; ++k) field = field - potential_v[mesh.tets[t][k]] * element.gradients[k];
        fields.electric_v_per_m.push_back(field);
        fields.current_a_per_m2.push_back(multiply(sigma, field));
    }
    return fields;
}

} // namespace tissuemesh::fem

#include "fem/compute_fields.h"

#include <algorithm>
#include <cstdint>

#include "core/error.h"
#include "fem/assemble.h"

namespace tissuemesh::fem {

TetFields compute_fields(const TetMesh& mesh, const Conductivities& conductivities,
                         const std::vector<double>& potential_v)
{
    if (potential_v.size() != mesh.vertex_count())
        throw InputError(concat("potential has ", potential_v.size(), " values but the mesh has ", mesh.vertex_count(),
                                " nodes; give one per node"));
    TetFields fields;
    fields.electric_v_per_m.resize(mesh.tet_count());
    fields.current_a_per_m2.resize(mesh.tet_count());
    const auto count = static_cast<std::int64_t>(mesh.tet_count());
    std::int64_t first_bad = count;
    // Per tet, in parallel; an exception may not leave the loop, so the first bad tet is redone outside.
#pragma omp parallel for schedule(static) reduction(min : first_bad)
    for (std::int64_t t = 0; t < count; ++t) {
        const auto tet = static_cast<std::size_t>(t);
        try {
            const Mat3& sigma = conductivities.of(mesh.tet_labels[tet], tet);
            const P1Element element = p1_element(mesh, tet);
            Vec3 field{0, 0, 0};
            for (int k = 0; k < 4; ++k) field = field - potential_v[mesh.tets[tet][k]] * element.gradients[k];
            fields.electric_v_per_m[tet] = field;
            fields.current_a_per_m2[tet] = multiply(sigma, field);
        } catch (...) {
            first_bad = std::min(first_bad, t);
        }
    }
    if (first_bad < count) {
        const auto tet = static_cast<std::size_t>(first_bad);
        conductivities.of(mesh.tet_labels[tet], tet);
        p1_element(mesh, tet);
    }
    return fields;
}

} // namespace tissuemesh::fem

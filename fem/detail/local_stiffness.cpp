#include "fem/detail/local_stiffness.h"

#include "core/error.h"

namespace tissuemesh::fem::detail {

SparseMatrix assemble_local_stiffness(const TetMesh& mesh, const LocalMesh& renumbered,
                                      const Conductivities& conductivities)
{
    try {
        return assemble_stiffness(renumbered.mesh, conductivities);
    } catch (const InputError&) {
        assemble_stiffness(mesh, conductivities);
        throw;
    }
}

} // namespace tissuemesh::fem::detail

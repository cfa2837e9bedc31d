// The stiffness matrix of a mesh renumbered for locality, with the caller's numbering in its errors.
#pragma once

#include "core/tet_mesh.h"
#include "fem/assemble.h"
#include "fem/detail/locality_order.h"

namespace tissuemesh::fem::detail {

/// assemble_stiffness() of `renumbered.mesh`. A bad tet or tissue is reported as `mesh` (the caller's
/// numbering) has it: on an InputError the original mesh is assembled again to throw its message.
/// @throws InputError as assemble_stiffness()
SparseMatrix assemble_local_stiffness(const TetMesh& mesh, const LocalMesh& renumbered,
                                      const Conductivities& conductivities);

} // namespace tissuemesh::fem::detail

// Per-tet electric field and current density of a P1 potential.
#pragma once

#include <vector>

#include "core/tet_mesh.h"
#include "fem/conductivities.h"

namespace tissuemesh::fem {

/// Constant fields of each tet (#T each), world axes.
struct TetFields {
    std::vector<Vec3> electric_v_per_m; ///< E = -grad(phi), V/m
    std::vector<Vec3> current_a_per_m2; ///< J = sigma E, A/m^2 (ohmic current; dipoles' primary
                                        ///< current is not included)
};

/// E and J from nodal potentials `potential_v` (#V, V).
/// @throws InputError when sizes disagree, a tissue has no conductivity or a tet is degenerate
TetFields compute_fields(const TetMesh& mesh, const Conductivities& conductivities,
                         const std::vector<double>& potential_v);

} // namespace tissuemesh::fem

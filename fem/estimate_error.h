// Element error indicator of a P1 potential, for solver-aware mesh refinement.
#pragma once

#include <vector>

#include "core/tet_mesh.h"
#include "fem/conductivities.h"

namespace tissuemesh::fem {

/// Flux-jump residual indicator per tet (#T): eta_T = sqrt(sum over the interior faces F of T of
/// 1/2 h_F |F| [J . n]_F^2), with J = -sigma grad(phi) (A/m^2), h_F the longest edge of F and |F| its
/// area (m, m^2): eta_T is in A / sqrt(m). P1 potentials have no element residual without sources, so the
/// jumps of the normal current carry the error; outer-boundary faces are left out (their flux is given).
/// Sum of eta_T^2 over the mesh behaves like the squared energy-norm error (order h^2 under uniform
/// refinement for smooth solutions). Large values mark the tets to refine first.
/// @throws InputError when sizes disagree, a tissue has no conductivity or a tet is degenerate
std::vector<double> estimate_error(const TetMesh& mesh, const Conductivities& conductivities,
                                   const std::vector<double>& potential_v);

} // namespace tissuemesh::fem

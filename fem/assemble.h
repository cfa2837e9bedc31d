// P1 (linear) finite elements on a labelled tet mesh: element gradients and the stiffness matrix.
//
// Units: the mesh is in mm; assembly converts positions to metres (x_m = 1e-3 * x_mm), so with
// conductivities in S/m the stiffness matrix is in S (A/V), right-hand sides are currents in A and
// solutions are potentials in V.
#pragma once

#include <array>
#include <cstddef>

#include <Eigen/SparseCore>

#include "core/tet_mesh.h"
#include "fem/conductivities.h"

namespace tissuemesh::fem {

/// Compressed sparse row matrix (#V by #V); column indices are sorted in every row.
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

/// Metres per millimetre: the one conversion between the mesh's mm and the solver's SI units.
inline constexpr double metres_per_mm = 1e-3;

/// The four constant gradients of a tet's hat functions (1/m, world axes) and its volume (m^3).
struct P1Element {
    std::array<Vec3, 4> gradients{};
    double volume_m3 = 0;
};

/// P1 element of tet `t`.
/// @throws InputError when the tet is degenerate or negatively oriented (names the tet and its volume)
P1Element p1_element(const TetMesh& mesh, std::size_t t);

/// Stiffness matrix K_ij = integral of grad(phi_i) . sigma grad(phi_j) over the mesh (S), sigma taken per
/// tet from `conductivities` by the tet's tissue. K is symmetric positive semi-definite with rows summing
/// to zero (constants are in its kernel: no boundary condition is applied here; the outer boundary is
/// insulated). K is exactly symmetric (one triangle of each element matrix is computed). Rows are
/// assembled in parallel (OpenMP) straight into compressed rows; each entry sums its tets in increasing tet
/// order, so the bytes are the same on every run and for any thread count.
/// @throws InputError when a tissue has no conductivity or a tet is degenerate
SparseMatrix assemble_stiffness(const TetMesh& mesh, const Conductivities& conductivities);

} // namespace tissuemesh::fem

// The FE system on the free nodes, once Dirichlet nodes (electrodes at a potential, the reference node) are
// taken out.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/vec3.h"
#include "fem/assemble.h"

namespace tissuemesh::fem::detail {

/// K_FF x_F = b_F - K_FD x_D on the free nodes, rows in Z-order of the free nodes' positions.
struct ReducedSystem {
    SparseMatrix matrix;
    Eigen::VectorXd rhs;
    std::vector<int> free_index; ///< #V: row of each free node, -1 for fixed ones
};

/// The system on the nodes whose `fixed` value is NaN; the others hold their potential (V). `rhs` may be
/// empty (then the reduced right-hand side is -K_FD x_D alone).
ReducedSystem reduce(const SparseMatrix& stiffness, const Eigen::VectorXd& rhs, const std::vector<double>& fixed,
                     const std::vector<Vec3>& nodes_mm);

} // namespace tissuemesh::fem::detail

// hypre's PCG with BoomerAMG as preconditioner (the only place that includes hypre's headers).
#pragma once

#include <Eigen/Core>

#include "fem/assemble.h"

namespace tissuemesh::fem::detail {

struct HyprePcgResult {
    Eigen::VectorXd solution;
    int iterations = 0;
    bool converged = false;
    double copy_seconds = 0;     ///< building hypre's matrix and vectors
    double setup_seconds = 0;    ///< BoomerAMG setup
    double iterate_seconds = 0;  ///< PCG iterations
};

/// Runs BoomerAMG-preconditioned CG on one MPI process (MPI and hypre are initialised on first use and
/// finalised at exit).
HyprePcgResult solve_with_boomeramg(const SparseMatrix& matrix, const Eigen::VectorXd& rhs, double tolerance,
                                    int max_iterations);

} // namespace tissuemesh::fem::detail

// hypre's PCG with BoomerAMG as preconditioner (the only place that includes hypre's headers).
#pragma once

#include <cstdint>
#include <vector>

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

/// One MPI process's share of a system: rows [first_row, first_row + row_count) of a global_rows x global_rows
/// matrix, as compressed rows with global column numbers.
struct RowBlock {
    std::int64_t global_rows = 0;
    std::int64_t first_row = 0;
    std::vector<int> starts;     ///< row_count + 1 offsets into columns and values, from 0
    std::vector<int> columns;    ///< global column of each entry
    std::vector<double> values;  ///< the entries
    std::vector<double> rhs;     ///< row_count entries of b
    std::int64_t row_count() const { return static_cast<std::int64_t>(rhs.size()); }
};

/// The same solver on several MPI processes (collective on MPI_COMM_WORLD, which must be initialised and
/// whose ranks hold consecutive blocks in rank order). The result's solution holds this block's rows.
HyprePcgResult solve_block_with_boomeramg(const RowBlock& block, double tolerance, int max_iterations);

} // namespace tissuemesh::fem::detail

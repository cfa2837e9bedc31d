// hypre's PCG with BoomerAMG as preconditioner (the only place that includes hypre's headers).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "fem/assemble.h"

namespace tissuemesh::fem::detail {

struct HyprePcgResult {
    Eigen::VectorXd solution;
    int iterations = 0;
    bool converged = false;
    double copy_seconds = 0;    ///< building hypre's matrix and vectors
    double setup_seconds = 0;   ///< BoomerAMG setup
    double iterate_seconds = 0; ///< PCG iterations
};

/// One MPI process's share of a system: rows [first_row, first_row + row_count) of a global_rows x global_rows
/// matrix, as compressed rows with global column numbers.
struct RowBlock {
    std::int64_t global_rows = 0;
    std::int64_t first_row = 0;
    std::vector<int> starts;    ///< row_count + 1 offsets into columns and values, from 0
    std::vector<int> columns;   ///< global column of each entry
    std::vector<double> values; ///< the entries
    std::int64_t row_count() const { return static_cast<std::int64_t>(starts.size()) - 1; }
};

/// What one right-hand side cost and reached.
struct PcgSolve {
    int iterations = 0;
    bool converged = false;
    double relative_residual = 0; ///< ||b - A x||_2 / ||b||_2 recomputed from x (0 for b = 0)
    double seconds = 0;           ///< the iterations and the residual check
};

/// BoomerAMG-CG with the hierarchy set up once, in the constructor, and used for every right-hand side
/// (the transfer matrices of lead fields solve one system for hundreds of them).
class AmgPcg {
public:
    /// The whole matrix on this one process (MPI and hypre are initialised on first use, finalised at exit).
    AmgPcg(const SparseMatrix& matrix, double tolerance, int max_iterations);
    /// This rank's block; collective on MPI_COMM_WORLD (initialised; ranks hold consecutive blocks in order).
    AmgPcg(const RowBlock& block, double tolerance, int max_iterations);
    ~AmgPcg();
    AmgPcg(const AmgPcg&) = delete;
    AmgPcg& operator=(const AmgPcg&) = delete;

    /// Solves A x = b from x = 0: `rhs` and `solution` hold this process's rows (local_rows() each).
    /// Collective when the matrix is spread over processes.
    PcgSolve solve(const double* rhs, double* solution);

    std::int64_t local_rows() const;
    double copy_seconds() const;  ///< building hypre's matrix and vectors
    double setup_seconds() const; ///< the BoomerAMG hierarchy

private:
    struct Objects;
    std::unique_ptr<Objects> objects_;
};

/// One solve with a fresh AmgPcg on this process.
HyprePcgResult solve_with_boomeramg(const SparseMatrix& matrix, const Eigen::VectorXd& rhs, double tolerance,
                                    int max_iterations);

} // namespace tissuemesh::fem::detail

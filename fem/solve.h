// Conjugate gradients for the symmetric positive definite systems of the FEM.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/progress.h"
#include "fem/assemble.h"

namespace tissuemesh::fem {

enum class Preconditioner {
    jacobi, ///< diagonal scaling (Eigen's CG): no dependency, fine for small meshes
    amg,    ///< hypre BoomerAMG as preconditioner of hypre's PCG: iterations nearly independent of size
};

/// Options for solve_spd().
struct SolverOptions {
    Preconditioner preconditioner = Preconditioner::amg; ///< see Preconditioner
    double relative_tolerance = 1e-10; ///< stop when ||b - A x||_2 / ||b||_2 falls below this (unitless)
    int max_iterations = 5000;         ///< iteration cap; reaching it without convergence throws
    /// MPI processes for the AMG-CG (tm-amg-worker under mpiexec; Debian's hypre has no threads, so this is
    /// how it uses more than one core). 1: in this process; 0: one per core this process may run on. Fewer
    /// are used when a process would get under min_unknowns_per_process; when the processes cannot run (no
    /// mpiexec, say) the solve warns and runs here.
    int processes = 1;
    /// Starting the processes and the file exchange cost about 0.7 s at 1 M unknowns: each must get at least this many
    /// unknowns.
    int min_unknowns_per_process = 100'000;
    std::string mpiexec = "mpiexec"; ///< the MPI launcher: a path, or a name looked up in PATH
};

/// What solve_spd() did.
struct SolverReport {
    std::string preconditioner;   ///< "jacobi" or "amg"
    int processes = 1;            ///< MPI processes the AMG-CG ran on
    int iterations = 0;           ///< CG iterations
    double relative_residual = 0; ///< ||b - A x||_2 / ||b||_2 recomputed from the returned x
    double seconds = 0;           ///< everything below, and the residual check
    double copy_seconds = 0;      ///< handing the system to the solver (hypre's own matrix and vectors)
    double setup_seconds = 0;     ///< preconditioner setup (the AMG hierarchy; the diagonal for jacobi)
    double iterate_seconds = 0;   ///< the CG iterations
};

/// Solves A x = b by preconditioned conjugate gradients from x = 0.
/// @pre  A is symmetric positive definite (apply a reference or Dirichlet condition to a stiffness matrix)
/// @throws InputError when sizes disagree or b is not finite
/// @throws AlgorithmError when the relative residual is above the tolerance after max_iterations (names
///         the iteration count, the residual reached and the fix)
Eigen::VectorXd solve_spd(const SparseMatrix& matrix, const Eigen::VectorXd& rhs, const SolverOptions& options = {},
                          const Progress& progress = {}, SolverReport* report = nullptr);

/// Fills right-hand side k into b (b holds #rows zeros on entry).
using RhsFiller = std::function<void(std::size_t k, Eigen::VectorXd& b)>;
/// Receives solution k: its values at the kept rows, in their order. After a failed start of the MPI
/// processes a sink may see a column again (the solve starts over in one process): store, do not accumulate.
using SolutionSink = std::function<void(std::size_t k, const double* kept_values)>;

/// What solve_spd_columns() did.
struct ColumnsReport {
    std::string preconditioner; ///< "jacobi" or "amg"
    int processes = 1;          ///< MPI processes the AMG-CG ran on
    std::size_t columns = 0;    ///< right-hand sides solved
    int min_iterations = 0, max_iterations = 0;
    double mean_iterations = 0;
    double max_relative_residual = 0; ///< the worst ||b - A x||_2 / ||b||_2 over the columns
    double seconds = 0;               ///< everything
    double prepare_seconds = 0;       ///< filling the right-hand sides and handing them over (processes only)
    double copy_seconds = 0;          ///< handing the matrix to the solver
    double setup_seconds = 0;         ///< the preconditioner, set up once
    double first_solve_seconds = 0;   ///< the iterations of the first column
    double later_solve_seconds = 0;   ///< mean iterations time of the other columns
};

/// Solves A x_k = b_k for k < `columns`, setting the preconditioner (the AMG hierarchy) up once: the
/// transfer matrices of lead fields solve one system for hundreds of right-hand sides. `rhs` fills each b_k
/// when it is needed; `sink` gets each x_k at `kept_rows` (every row when empty) in order, as soon as it is
/// solved. Progress: the fraction of columns done, and an info line every tenth with the time left.
/// @pre  A is symmetric positive definite
/// @throws InputError when A is not square or a b_k is not finite
/// @throws AlgorithmError when a column's relative residual stays above the tolerance (see solve_spd)
/// Exceptions of `rhs` and `sink` propagate.
void solve_spd_columns(const SparseMatrix& matrix, std::size_t columns, const RhsFiller& rhs,
                       const std::vector<std::uint32_t>& kept_rows, const SolutionSink& sink,
                       const SolverOptions& options = {}, const Progress& progress = {},
                       ColumnsReport* report = nullptr);

} // namespace tissuemesh::fem

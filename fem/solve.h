// Conjugate gradients for the symmetric positive definite systems of the FEM.
#pragma once

#include <string>

#include <Eigen/Core>

#include "core/progress.h"
#include "fem/assemble.h"

namespace tissuemesh::fem {

enum class Preconditioner {
    jacobi,  ///< diagonal scaling (Eigen's CG): no dependency, fine for small meshes
    amg,     ///< hypre BoomerAMG as preconditioner of hypre's PCG: iterations nearly independent of size
};

/// Options for solve_spd().
struct SolverOptions {
    Preconditioner preconditioner = Preconditioner::amg;  ///< see Preconditioner
    double relative_tolerance = 1e-10;  ///< stop when ||b - A x||_2 / ||b||_2 falls below this (unitless)
    int max_iterations = 5000;          ///< iteration cap; reaching it without convergence throws
    /// MPI processes for the AMG-CG (tm-amg-worker under mpiexec; Debian's hypre has no threads, so this is
    /// how it uses more than one core). 1: in this process; 0: one per core this process may run on. Fewer
    /// are used when a process would get under min_unknowns_per_process; when the processes cannot run (no
    /// mpiexec, say) the solve warns and runs here.
    int processes = 1;
    /// Starting the processes and the file exchange cost about 0.7 s at 1 M unknowns: each must get at least this many unknowns.
    int min_unknowns_per_process = 100'000;
    std::string mpiexec = "mpiexec";  ///< the MPI launcher: a path, or a name looked up in PATH
};

/// What solve_spd() did.
struct SolverReport {
    std::string preconditioner;      ///< "jacobi" or "amg"
    int processes = 1;               ///< MPI processes the AMG-CG ran on
    int iterations = 0;              ///< CG iterations
    double relative_residual = 0;    ///< ||b - A x||_2 / ||b||_2 recomputed from the returned x
    double seconds = 0;              ///< everything below, and the residual check
    double copy_seconds = 0;         ///< handing the system to the solver (hypre's own matrix and vectors)
    double setup_seconds = 0;        ///< preconditioner setup (the AMG hierarchy; the diagonal for jacobi)
    double iterate_seconds = 0;      ///< the CG iterations
};

/// Solves A x = b by preconditioned conjugate gradients from x = 0.
/// @pre  A is symmetric positive definite (apply a reference or Dirichlet condition to a stiffness matrix)
/// @throws InputError when sizes disagree or b is not finite
/// @throws AlgorithmError when the relative residual is above the tolerance after max_iterations (names
///         the iteration count, the residual reached and the fix)
Eigen::VectorXd solve_spd(const SparseMatrix& matrix, const Eigen::VectorXd& rhs, const SolverOptions& options = {},
                          const Progress& progress = {}, SolverReport* report = nullptr);

} // namespace tissuemesh::fem

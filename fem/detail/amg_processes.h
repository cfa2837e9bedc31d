// BoomerAMG-CG on several MPI processes: Debian's hypre has no threads, so a second core is used by a
// second process. tm-solve stays one program: it starts the processes itself.
#pragma once

#include <optional>
#include <string>

#include <Eigen/Core>

#include "fem/assemble.h"
#include "fem/detail/amg_exchange.h"
#include "fem/detail/hypre_pcg.h"

namespace tissuemesh::fem::detail {

/// How to start the processes.
struct ProcessLaunch {
    int processes = 2;                ///< MPI ranks
    std::string mpiexec = "mpiexec";  ///< the launcher: a path, or a name looked up in PATH
};

/// Solves A x = b with BoomerAMG-CG on several MPI processes: the system goes to a temporary folder,
/// `mpiexec -n P tm-amg-worker` (the worker next to the running program) solves it, and the solution
/// comes back through a file (amg_exchange.h). The result's times are rank 0's.
/// Returns nothing and says why in `why_not` when the processes could not do it: no mpiexec or worker,
/// MPI not started within a minute, or a worker that failed. The caller then solves in its own process.
std::optional<HyprePcgResult> solve_on_processes(const SparseMatrix& matrix, const Eigen::VectorXd& rhs,
                                                 const SolveRequest& request, const ProcessLaunch& launch,
                                                 std::string& why_not);

/// The cores this process may run on (its CPU affinity mask), at least 1.
int available_cores();

} // namespace tissuemesh::fem::detail

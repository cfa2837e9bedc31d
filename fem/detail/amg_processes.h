// BoomerAMG-CG on several MPI processes: Debian's hypre has no threads, so a second core is used by a
// second process. tm-solve and tm-leadfield stay one program each: they start the processes themselves.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fem/assemble.h"
#include "fem/detail/amg_exchange.h"
#include "fem/detail/hypre_pcg.h"

namespace tissuemesh::fem::detail {

/// How to start the processes.
struct ProcessLaunch {
    int processes = 2;               ///< MPI ranks
    std::string mpiexec = "mpiexec"; ///< the launcher: a path, or a name looked up in PATH
};

/// Fills right-hand side k into b (zeros on entry, #rows entries).
using ColumnFiller = std::function<void(std::size_t k, Eigen::VectorXd& b)>;
/// Receives solution k: its values at the kept rows (all rows when none are named), and what it cost.
using ColumnSink = std::function<void(std::size_t k, const PcgSolve& solve, const double* kept_values)>;

/// What the processes reported besides the solutions.
struct ColumnsResult {
    std::vector<PcgSolve> solves; ///< one per right-hand side, in order
    double copy_seconds = 0;      ///< rank 0's
    double setup_seconds = 0;     ///< the BoomerAMG hierarchy, set up once
};

/// Solves A x_k = b_k for k < `columns` with BoomerAMG-CG on several MPI processes: the system and every
/// right-hand side go to a temporary folder, `mpiexec -n P tm-amg-worker` (the worker next to the running
/// program) sets BoomerAMG up once and solves them in turn, and each solution comes back through a file as
/// soon as it is done, to `sink` (in order, from this thread: progress can be reported there).
/// Returns nothing and says why in `why_not` when the processes could not do it all: no mpiexec or worker,
/// MPI not started within a minute, or a worker that failed. The caller then solves in its own process, and
/// its sink may see columns again: it must store, not accumulate. Exceptions of `rhs` and `sink` propagate
/// (the processes are stopped).
std::optional<ColumnsResult> solve_columns_on_processes(const SparseMatrix& matrix, std::size_t columns,
                                                        const ColumnFiller& rhs,
                                                        const std::vector<std::uint32_t>& kept_rows,
                                                        const ColumnSink& sink, const SolveRequest& request,
                                                        const ProcessLaunch& launch, std::string& why_not);

/// The cores this process may run on (its CPU affinity mask), at least 1.
int available_cores();

} // namespace tissuemesh::fem::detail

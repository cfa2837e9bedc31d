// The body of tm-amg-worker: one MPI rank of an AMG-CG solve that tm-solve hands out (fem/detail/amg_processes.h).
#pragma once

namespace tissuemesh::fem::detail {

/// Runs under mpiexec as `tm-amg-worker SYSTEM RESULT STARTED`: rank 0 creates STARTED once MPI is up,
/// every rank solves its block of the system file SYSTEM (amg_exchange.h), and rank 0 writes the whole
/// solution to RESULT (atomically). Returns the exit status; on an error every rank is aborted.
int run_amg_worker(int argc, char** argv);

} // namespace tissuemesh::fem::detail

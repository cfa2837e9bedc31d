// The body of tm-amg-worker: one MPI rank of an AMG-CG solve that a solve hands out (fem/detail/amg_processes.h).
#pragma once

namespace tissuemesh::fem::detail {

/// Runs under mpiexec as `tm-amg-worker SYSTEM RESULT STARTED`: rank 0 creates STARTED once MPI is up,
/// every rank reads its block of the system file SYSTEM (amg_exchange.h), BoomerAMG is set up once, and each
/// right-hand side is solved in turn; rank 0 appends each solution's kept rows to RESULT as it comes (under
/// a temporary name, renamed when all are in). Returns the exit status; on an error every rank is aborted.
int run_amg_worker(int argc, char** argv);

} // namespace tissuemesh::fem::detail

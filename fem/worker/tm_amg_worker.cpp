// tm-amg-worker: one MPI rank of tm-solve's AMG-CG when it runs on several processes (not a user step).
#include "fem/detail/hypre_worker.h"

int main(int argc, char** argv) { return tissuemesh::fem::detail::run_amg_worker(argc, argv); }

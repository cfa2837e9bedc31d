#include "fem/detail/hypre_worker.h"

#include <cstdio>
#include <exception>
#include <filesystem>
#include <vector>

#include <mpi.h>

#include <HYPRE_utilities.h>

#include "fem/detail/amg_exchange.h"
#include "fem/detail/hypre_pcg.h"

namespace tissuemesh::fem::detail {
namespace {

// Rank 0 collects every block's rows in rank order (the blocks are consecutive) and writes the result.
void gather_and_write(const HyprePcgResult& part, std::int64_t global_rows, int rank, int size,
                      const std::filesystem::path& output)
{
    int mine = static_cast<int>(part.solution.size());
    std::vector<int> counts(static_cast<std::size_t>(size)), offsets(static_cast<std::size_t>(size), 0);
    MPI_Gather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    HyprePcgResult whole = part;
    if (rank == 0) {
        for (std::size_t r = 1; r < counts.size(); ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
        whole.solution.resize(global_rows);
    }
    MPI_Gatherv(part.solution.data(), mine, MPI_DOUBLE, whole.solution.data(), counts.data(), offsets.data(),
                MPI_DOUBLE, 0, MPI_COMM_WORLD);
    if (rank != 0) return;
    std::filesystem::path partial = output;
    partial += ".part";
    write_result_file(partial, whole);
    std::filesystem::rename(partial, output);
}

} // namespace

int run_amg_worker(int argc, char** argv)
{
    if (argc != 4) {
        std::fprintf(stderr, "tm-amg-worker: internal to tm-solve, which starts it under mpiexec as "
                             "tm-amg-worker SYSTEM RESULT STARTED; run tm-solve instead\n");
        return 2;
    }
    MPI_Init(&argc, &argv);
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    if (rank == 0)
        if (std::FILE* started = std::fopen(argv[3], "wb")) std::fclose(started);
    HYPRE_Init();
    try {
        SolveRequest request;
        const RowBlock block = read_row_block(argv[1], rank, size, request);
        const HyprePcgResult part = solve_block_with_boomeramg(block, request.tolerance, request.max_iterations);
        gather_and_write(part, block.global_rows, rank, size, argv[2]);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "tm-amg-worker (rank %d of %d): %s\n", rank, size, error.what());
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    HYPRE_Finalize();
    MPI_Finalize();
    return 0;
}

} // namespace tissuemesh::fem::detail

#include "fem/detail/hypre_worker.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <optional>
#include <vector>

#include <mpi.h>

#include <HYPRE_utilities.h>

#include "fem/detail/amg_exchange.h"
#include "fem/detail/hypre_pcg.h"

namespace tissuemesh::fem::detail {
namespace {

// This block's values at the kept rows (increasing), gathered on rank 0 in rank order: the blocks are
// consecutive, so that is the order of the kept rows.
std::vector<double> gather_kept(const SystemFileReader& system, const std::vector<double>& solution, int rank, int size)
{
    const RowBlock& block = system.block();
    const std::vector<std::int64_t>& kept = system.kept_rows();
    const auto first = std::lower_bound(kept.begin(), kept.end(), block.first_row);
    const auto last = std::lower_bound(first, kept.end(), block.first_row + block.row_count());
    std::vector<double> mine;
    for (auto row = first; row != last; ++row)
        mine.push_back(solution[static_cast<std::size_t>(*row - block.first_row)]);
    int count = static_cast<int>(mine.size());
    std::vector<int> counts(static_cast<std::size_t>(size)), offsets(static_cast<std::size_t>(size), 0);
    MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    std::vector<double> whole;
    if (rank == 0) {
        for (std::size_t r = 1; r < counts.size(); ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
        whole.resize(kept.size());
    }
    MPI_Gatherv(mine.data(), count, MPI_DOUBLE, whole.data(), counts.data(), offsets.data(), MPI_DOUBLE, 0,
                MPI_COMM_WORLD);
    return whole;
}

} // namespace

int run_amg_worker(int argc, char** argv)
{
    if (argc != 4) {
        std::fprintf(stderr, "tm-amg-worker: internal to tm-solve and tm-leadfield, which start it under mpiexec as "
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
        SystemFileReader system(argv[1], rank, size);
        const SolveRequest request = system.request();
        std::optional<ResultFileWriter> result;
        {
            AmgPcg pcg(system.block(), request.tolerance, request.max_iterations);
            if (rank == 0)
                result.emplace(argv[2], system.columns(), static_cast<std::int64_t>(system.kept_rows().size()),
                               pcg.copy_seconds(), pcg.setup_seconds());
            std::vector<double> rhs, solution(static_cast<std::size_t>(pcg.local_rows()));
            for (std::int64_t k = 0; k < system.columns(); ++k) {
                system.next_column(rhs);
                const PcgSolve solve = pcg.solve(rhs.data(), solution.data());
                const std::vector<double> kept = gather_kept(system, solution, rank, size);
                if (rank == 0) result->add(solve, kept);
            }
        }
        if (rank == 0) result->finish();
    } catch (const std::exception& error) {
        std::fprintf(stderr, "tm-amg-worker (rank %d of %d): %s\n", rank, size, error.what());
        MPI_Abort(MPI_COMM_WORLD, 1);
    }
    HYPRE_Finalize();
    MPI_Finalize();
    return 0;
}

} // namespace tissuemesh::fem::detail

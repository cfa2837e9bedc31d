#include "fem/detail/hypre_pcg.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <type_traits>
#include <utility>
#include <vector>

#include <mpi.h>

#include <HYPRE.h>
#include <HYPRE_IJ_mv.h>
#include <HYPRE_krylov.h>
#include <HYPRE_parcsr_ls.h>
#include <HYPRE_parcsr_mv.h>
#include <_hypre_parcsr_mv.h>

#include "core/error.h"

namespace tissuemesh::fem::detail {
namespace {

void finalise_hypre()
{
    HYPRE_Finalize();
    int finalised = 0;
    MPI_Finalized(&finalised);
    if (!finalised) MPI_Finalize();
}

// Debian's hypre is built against MPI: a single process runs as an MPI singleton. MPI may be initialised
// only once per process, hence the function-local static.
void ensure_initialised()
{
    static const bool initialised = [] {
        int mpi_initialised = 0;
        MPI_Initialized(&mpi_initialised);
        if (!mpi_initialised) MPI_Init(nullptr, nullptr);
        HYPRE_Init();
        std::atexit(finalise_hypre);
        return true;
    }();
    (void)initialised;
}

// Owns the hypre objects of one solve; destroys them whatever happens.
struct HypreObjects {
    HYPRE_ParCSRMatrix matrix = nullptr;
    HYPRE_ParVector rhs = nullptr;
    HYPRE_ParVector solution = nullptr;
    HYPRE_Solver pcg = nullptr;
    HYPRE_Solver amg = nullptr;
    bool borrowed = false;  ///< matrix and vectors belong to IJ objects
    ~HypreObjects()
    {
        if (amg) HYPRE_BoomerAMGDestroy(amg);
        if (pcg) HYPRE_ParCSRPCGDestroy(pcg);
        if (borrowed) return;
        if (solution) HYPRE_ParVectorDestroy(solution);
        if (rhs) HYPRE_ParVectorDestroy(rhs);
        if (matrix) HYPRE_ParCSRMatrixDestroy(matrix);
    }
};

// A vector of n zeros; one process owns every row: rows [0, n) on rank 0.
HYPRE_ParVector make_vector(HYPRE_BigInt n)
{
    HYPRE_BigInt partitioning[2] = {0, n};
    HYPRE_ParVector vector = nullptr;
    HYPRE_ParVectorCreate(MPI_COMM_WORLD, n, partitioning, &vector);
    HYPRE_ParVectorInitialize(vector);
    HYPRE_ParVectorSetConstantValues(vector, 0.0);
    return vector;
}

double* values_of(HYPRE_ParVector vector)
{
    return hypre_VectorData(hypre_ParVectorLocalVector(vector));
}

// The matrix straight into hypre's ParCSR form, without the IJ interface, which stages every entry and then
// copies it again (0.99 s for 1.04 M rows, against 0.17 s this way). On one process the whole matrix is the
// "diagonal" block, stored as compressed rows whose first entry is the diagonal one, as hypre's smoothers expect.
HYPRE_ParCSRMatrix make_matrix(const SparseMatrix& source)
{
    const auto n = static_cast<HYPRE_BigInt>(source.rows());
    const auto nonzeros = static_cast<HYPRE_Int>(source.nonZeros());
    HYPRE_BigInt partitioning[2] = {0, n};
    HYPRE_ParCSRMatrix matrix = nullptr;
    HYPRE_ParCSRMatrixCreate(MPI_COMM_WORLD, n, n, partitioning, partitioning, 0, nonzeros, 0, &matrix);
    HYPRE_ParCSRMatrixInitialize(matrix);
    hypre_CSRMatrix* block = hypre_ParCSRMatrixDiag(matrix);
    HYPRE_Int* starts = hypre_CSRMatrixI(block);
    HYPRE_Int* columns = hypre_CSRMatrixJ(block);
    double* values = hypre_CSRMatrixData(block);
    const int* source_starts = source.outerIndexPtr();
    const int* source_columns = source.innerIndexPtr();
    const double* source_values = source.valuePtr();
    static_assert(std::is_same_v<HYPRE_Int, SparseMatrix::StorageIndex>);
    std::copy(source_starts, source_starts + n + 1, starts);
    const auto rows = static_cast<std::int64_t>(n);
    std::int64_t missing_diagonal = -1;
#pragma omp parallel for schedule(static) reduction(max : missing_diagonal)
    for (std::int64_t row = 0; row < rows; ++row) {
        HYPRE_Int at = source_starts[row];
        const HYPRE_Int end = source_starts[row + 1];
        // The diagonal first, then the other columns in increasing order.
        HYPRE_Int diagonal = -1;
        for (HYPRE_Int k = at; k < end; ++k)
            if (source_columns[k] == row) diagonal = k;
        if (diagonal < 0) {
            missing_diagonal = std::max(missing_diagonal, row);
            continue;
        }
        columns[at] = static_cast<HYPRE_Int>(row);
        values[at++] = source_values[diagonal];
        for (HYPRE_Int k = source_starts[row]; k < end; ++k)
            if (k != diagonal) {
                columns[at] = source_columns[k];
                values[at++] = source_values[k];
            }
    }
    if (missing_diagonal >= 0) {
        HYPRE_ParCSRMatrixDestroy(matrix);
        throw AlgorithmError(concat("linear system: row ", missing_diagonal, " has no diagonal entry"));
    }
    hypre_CSRMatrixNumRownnz(block) = static_cast<HYPRE_Int>(n);
    hypre_ParCSRMatrixSetNumNonzeros(matrix);
    hypre_ParCSRMatrixSetDNumNonzeros(matrix);
    return matrix;
}

// Settings for 3D scalar elliptic problems (hypre's manual): HMIS coarsening, extended+i interpolation
// truncated to 4 entries, strength threshold 0.5, one V-cycle with one forward Gauss-Seidel sweep on the way
// down and one backward sweep on the way up: the cycle stays symmetric, as CG needs, at half the smoothing
// of a symmetric sweep on both legs (measured on the 1.04 M-node tDCS problem of bench/solve, one thread:
// AMG setup plus iterations 11.4-12.3 s -> 7.4-8.4 s, 22 -> 25 iterations). Aggressive coarsening on the
// first level (multipass interpolation) cut the operator complexity and the setup: measured on a 0.9 M-node
// tDCS problem to 1e-8, 15 -> 22 iterations but 51 -> 38 CPU seconds for the whole solve (bench/SOLVE.md).
// The transposed interpolation is kept for the restriction of every cycle (on that problem 2.6 -> 2.1 s
// setup, 6.9 -> 6.0 s of iterations, medians of 3 on a noisy machine). Tried on the 1.04 M-node problem
// with the split smoother, and slower: two aggressive levels (33 iterations), threshold 0.6 (28), and
// interpolation truncated to 3 entries (26).
HYPRE_Solver make_boomeramg()
{
    HYPRE_Solver amg = nullptr;
    HYPRE_BoomerAMGCreate(&amg);
    HYPRE_BoomerAMGSetPrintLevel(amg, 0);
    HYPRE_BoomerAMGSetCoarsenType(amg, 10);
    HYPRE_BoomerAMGSetInterpType(amg, 6);
    HYPRE_BoomerAMGSetPMaxElmts(amg, 4);
    HYPRE_BoomerAMGSetStrongThreshold(amg, 0.5);
    HYPRE_BoomerAMGSetAggNumLevels(amg, 1);
    HYPRE_BoomerAMGSetAggInterpType(amg, 4);
    HYPRE_BoomerAMGSetRelaxType(amg, 6);  // then split below; the coarsest level is solved directly
    HYPRE_BoomerAMGSetCycleRelaxType(amg, 13, 1);  // down: forward l1-Gauss-Seidel
    HYPRE_BoomerAMGSetCycleRelaxType(amg, 14, 2);  // up: backward l1-Gauss-Seidel
    HYPRE_BoomerAMGSetNumSweeps(amg, 1);
    HYPRE_BoomerAMGSetTol(amg, 0.0);
    HYPRE_BoomerAMGSetMaxIter(amg, 1);
    HYPRE_BoomerAMGSetKeepTranspose(amg, 1);
    return amg;
}

double seconds_since(std::chrono::steady_clock::time_point since)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// Runs the PCG on objects whose matrix and vectors are built; fills the counts and times of `result`.
void run_pcg(HypreObjects& objects, double tolerance, int max_iterations, HyprePcgResult& result)
{
    HYPRE_ParCSRPCGCreate(MPI_COMM_WORLD, &objects.pcg);
    HYPRE_PCGSetMaxIter(objects.pcg, max_iterations);
    HYPRE_PCGSetTol(objects.pcg, tolerance);
    HYPRE_PCGSetTwoNorm(objects.pcg, 1);  // stop on ||r||_2 / ||b||_2, the measure we report
    HYPRE_PCGSetPrintLevel(objects.pcg, 0);
    HYPRE_PCGSetLogging(objects.pcg, 1);
    objects.amg = make_boomeramg();
    HYPRE_PCGSetPrecond(objects.pcg, reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSolve),
                        reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSetup), objects.amg);
    auto start = std::chrono::steady_clock::now();
    HYPRE_ParCSRPCGSetup(objects.pcg, objects.matrix, objects.rhs, objects.solution);
    result.setup_seconds = seconds_since(start);
    start = std::chrono::steady_clock::now();
    HYPRE_ParCSRPCGSolve(objects.pcg, objects.matrix, objects.rhs, objects.solution);
    result.iterate_seconds = seconds_since(start);
    HYPRE_ClearAllErrors();  // non-convergence is reported through the result, not hypre's error flag

    HYPRE_Int iterations = 0;
    HYPRE_Int converged = 0;
    HYPRE_PCGGetNumIterations(objects.pcg, &iterations);
    HYPRE_PCGGetConverged(objects.pcg, &converged);
    result.iterations = iterations;
    result.converged = converged != 0;
}

} // namespace

HyprePcgResult solve_with_boomeramg(const SparseMatrix& matrix, const Eigen::VectorXd& rhs, double tolerance,
                                    int max_iterations)
{
    ensure_initialised();
    const auto start = std::chrono::steady_clock::now();
    HyprePcgResult result;
    const auto n = static_cast<HYPRE_BigInt>(matrix.rows());
    HypreObjects objects;
    objects.matrix = make_matrix(matrix);
    objects.rhs = make_vector(n);
    std::copy(rhs.data(), rhs.data() + n, values_of(objects.rhs));
    objects.solution = make_vector(n);
    result.copy_seconds = seconds_since(start);
    run_pcg(objects, tolerance, max_iterations, result);
    result.solution.resize(matrix.rows());
    const double* solution = values_of(objects.solution);
    std::copy(solution, solution + n, result.solution.data());
    return result;
}

// Across processes the matrix goes through hypre's IJ interface, which works out the columns each process
// needs from the others (the off-diagonal blocks) and puts each row's diagonal entry first.
HyprePcgResult solve_block_with_boomeramg(const RowBlock& block, double tolerance, int max_iterations)
{
    const auto start = std::chrono::steady_clock::now();
    HyprePcgResult result;
    const auto rows = static_cast<HYPRE_Int>(block.row_count());
    const auto first = static_cast<HYPRE_BigInt>(block.first_row);
    const HYPRE_BigInt last = first + rows - 1;
    std::vector<HYPRE_Int> sizes(static_cast<std::size_t>(rows));
    std::vector<HYPRE_BigInt> row_numbers(static_cast<std::size_t>(rows));
    for (HYPRE_Int r = 0; r < rows; ++r) {
        sizes[static_cast<std::size_t>(r)] = block.starts[static_cast<std::size_t>(r) + 1] - block.starts[static_cast<std::size_t>(r)];
        row_numbers[static_cast<std::size_t>(r)] = first + r;
    }
    HYPRE_IJMatrix ij_matrix = nullptr;
    HYPRE_IJVector ij_rhs = nullptr, ij_solution = nullptr;
    HYPRE_IJMatrixCreate(MPI_COMM_WORLD, first, last, first, last, &ij_matrix);
    HYPRE_IJMatrixSetObjectType(ij_matrix, HYPRE_PARCSR);
    HYPRE_IJMatrixSetRowSizes(ij_matrix, sizes.data());
    HYPRE_IJMatrixInitialize(ij_matrix);
    HYPRE_IJMatrixSetValues(ij_matrix, rows, sizes.data(), row_numbers.data(), block.columns.data(), block.values.data());
    HYPRE_IJMatrixAssemble(ij_matrix);
    const std::vector<double> zeros(static_cast<std::size_t>(rows), 0.0);
    for (auto [vector, values] : {std::pair{&ij_rhs, block.rhs.data()}, std::pair{&ij_solution, zeros.data()}}) {
        HYPRE_IJVectorCreate(MPI_COMM_WORLD, first, last, vector);
        HYPRE_IJVectorSetObjectType(*vector, HYPRE_PARCSR);
        HYPRE_IJVectorInitialize(*vector);
        HYPRE_IJVectorSetValues(*vector, rows, row_numbers.data(), values);
        HYPRE_IJVectorAssemble(*vector);
    }
    // The IJ objects own the ParCSR ones: HypreObjects only borrows them, the IJ ones are destroyed last.
    struct IjOwner {
        HYPRE_IJMatrix& matrix;
        HYPRE_IJVector &rhs, &solution;
        ~IjOwner()
        {
            HYPRE_IJVectorDestroy(solution);
            HYPRE_IJVectorDestroy(rhs);
            HYPRE_IJMatrixDestroy(matrix);
        }
    } ij_owner{ij_matrix, ij_rhs, ij_solution};
    HypreObjects objects;
    void* object = nullptr;
    HYPRE_IJMatrixGetObject(ij_matrix, &object);
    objects.matrix = static_cast<HYPRE_ParCSRMatrix>(object);
    HYPRE_IJVectorGetObject(ij_rhs, &object);
    objects.rhs = static_cast<HYPRE_ParVector>(object);
    HYPRE_IJVectorGetObject(ij_solution, &object);
    objects.solution = static_cast<HYPRE_ParVector>(object);
    objects.borrowed = true;
    result.copy_seconds = seconds_since(start);
    run_pcg(objects, tolerance, max_iterations, result);
    result.solution.resize(rows);
    const double* solution = values_of(objects.solution);
    std::copy(solution, solution + rows, result.solution.data());
    return result;
}

} // namespace tissuemesh::fem::detail

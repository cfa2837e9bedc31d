#include "fem/detail/hypre_pcg.h"

#include <algorithm>
#include <cmath>
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

// A vector of this process's rows [first, first + count) of `global` rows, zeros.
HYPRE_ParVector make_vector(HYPRE_BigInt first, HYPRE_BigInt count, HYPRE_BigInt global)
{
    HYPRE_BigInt partitioning[2] = {first, first + count};
    HYPRE_ParVector vector = nullptr;
    HYPRE_ParVectorCreate(MPI_COMM_WORLD, global, partitioning, &vector);
    HYPRE_ParVectorInitialize(vector);
    HYPRE_ParVectorSetConstantValues(vector, 0.0);
    return vector;
}

double* values_of(HYPRE_ParVector vector) { return hypre_VectorData(hypre_ParVectorLocalVector(vector)); }

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
    HYPRE_BoomerAMGSetRelaxType(amg, 6);          // then split below; the coarsest level is solved directly
    HYPRE_BoomerAMGSetCycleRelaxType(amg, 13, 1); // down: forward l1-Gauss-Seidel
    HYPRE_BoomerAMGSetCycleRelaxType(amg, 14, 2); // up: backward l1-Gauss-Seidel
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

} // namespace

// The hypre objects of one system: the matrix (owned directly on one process, through its IJ object across
// processes), the right-hand side, solution and residual vectors of this process's rows, and the solvers.
struct AmgPcg::Objects {
    HYPRE_IJMatrix ij_matrix = nullptr;
    HYPRE_ParCSRMatrix matrix = nullptr;
    HYPRE_ParVector rhs = nullptr, solution = nullptr, residual = nullptr;
    HYPRE_Solver pcg = nullptr, amg = nullptr;
    HYPRE_BigInt first = 0, rows = 0, global = 0;
    double copy_seconds = 0, setup_seconds = 0;

    ~Objects()
    {
        if (amg) HYPRE_BoomerAMGDestroy(amg);
        if (pcg) HYPRE_ParCSRPCGDestroy(pcg);
        for (HYPRE_ParVector vector : {residual, solution, rhs})
            if (vector) HYPRE_ParVectorDestroy(vector);
        if (ij_matrix) HYPRE_IJMatrixDestroy(ij_matrix);
        else if (matrix) HYPRE_ParCSRMatrixDestroy(matrix);
    }

    // The vectors and the PCG with its BoomerAMG hierarchy (the expensive part, done once).
    void set_up(double tolerance, int max_iterations)
    {
        rhs = make_vector(first, rows, global);
        solution = make_vector(first, rows, global);
        residual = make_vector(first, rows, global);
        HYPRE_ParCSRPCGCreate(MPI_COMM_WORLD, &pcg);
        HYPRE_PCGSetMaxIter(pcg, max_iterations);
        HYPRE_PCGSetTol(pcg, tolerance);
        HYPRE_PCGSetTwoNorm(pcg, 1); // stop on ||r||_2 / ||b||_2, the measure we report
        HYPRE_PCGSetPrintLevel(pcg, 0);
        HYPRE_PCGSetLogging(pcg, 1);
        amg = make_boomeramg();
        HYPRE_PCGSetPrecond(pcg, reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSolve),
                            reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSetup), amg);
        const auto start = std::chrono::steady_clock::now();
        HYPRE_ParCSRPCGSetup(pcg, matrix, rhs, solution);
        setup_seconds = seconds_since(start);
    }
};

AmgPcg::AmgPcg(const SparseMatrix& matrix, double tolerance, int max_iterations) : objects_(std::make_unique<Objects>())
{
    ensure_initialised();
    const auto start = std::chrono::steady_clock::now();
    objects_->rows = objects_->global = static_cast<HYPRE_BigInt>(matrix.rows());
    objects_->matrix = make_matrix(matrix);
    objects_->copy_seconds = seconds_since(start);
    objects_->set_up(tolerance, max_iterations);
}

// Across processes the matrix goes through hypre's IJ interface, which works out the columns each process
// needs from the others (the off-diagonal blocks) and puts each row's diagonal entry first.
AmgPcg::AmgPcg(const RowBlock& block, double tolerance, int max_iterations) : objects_(std::make_unique<Objects>())
{
    const auto start = std::chrono::steady_clock::now();
    const auto rows = static_cast<HYPRE_Int>(block.row_count());
    const auto first = static_cast<HYPRE_BigInt>(block.first_row);
    objects_->first = first;
    objects_->rows = rows;
    objects_->global = static_cast<HYPRE_BigInt>(block.global_rows);
    std::vector<HYPRE_Int> sizes(static_cast<std::size_t>(rows));
    std::vector<HYPRE_BigInt> row_numbers(static_cast<std::size_t>(rows));
    for (HYPRE_Int r = 0; r < rows; ++r) {
        sizes[static_cast<std::size_t>(r)] =
            block.starts[static_cast<std::size_t>(r) + 1] - block.starts[static_cast<std::size_t>(r)];
        row_numbers[static_cast<std::size_t>(r)] = first + r;
    }
    HYPRE_IJMatrixCreate(MPI_COMM_WORLD, first, first + rows - 1, first, first + rows - 1, &objects_->ij_matrix);
    HYPRE_IJMatrixSetObjectType(objects_->ij_matrix, HYPRE_PARCSR);
    HYPRE_IJMatrixSetRowSizes(objects_->ij_matrix, sizes.data());
    HYPRE_IJMatrixInitialize(objects_->ij_matrix);
    HYPRE_IJMatrixSetValues(objects_->ij_matrix, rows, sizes.data(), row_numbers.data(), block.columns.data(),
                            block.values.data());
    HYPRE_IJMatrixAssemble(objects_->ij_matrix);
    void* object = nullptr;
    HYPRE_IJMatrixGetObject(objects_->ij_matrix, &object);
    objects_->matrix = static_cast<HYPRE_ParCSRMatrix>(object);
    objects_->copy_seconds = seconds_since(start);
    objects_->set_up(tolerance, max_iterations);
}

AmgPcg::~AmgPcg() = default;

PcgSolve AmgPcg::solve(const double* rhs, double* solution)
{
    const auto start = std::chrono::steady_clock::now();
    Objects& o = *objects_;
    const auto rows = static_cast<std::size_t>(o.rows);
    std::copy(rhs, rhs + rows, values_of(o.rhs));
    HYPRE_ParVectorSetConstantValues(o.solution, 0.0);
    PcgSolve result;
    double rhs_norm2 = 0;
    HYPRE_ParVectorInnerProd(o.rhs, o.rhs, &rhs_norm2);
    if (rhs_norm2 > 0) {
        HYPRE_ParCSRPCGSolve(o.pcg, o.matrix, o.rhs, o.solution);
        HYPRE_ClearAllErrors(); // non-convergence is reported through the result, not hypre's error flag
        HYPRE_Int iterations = 0, converged = 0;
        HYPRE_PCGGetNumIterations(o.pcg, &iterations);
        HYPRE_PCGGetConverged(o.pcg, &converged);
        result.iterations = iterations;
        result.converged = converged != 0;
        // The true residual b - A x, not the recurrence's estimate.
        HYPRE_ParVectorCopy(o.rhs, o.residual);
        HYPRE_ParCSRMatrixMatvec(-1.0, o.matrix, o.solution, 1.0, o.residual);
        double residual_norm2 = 0;
        HYPRE_ParVectorInnerProd(o.residual, o.residual, &residual_norm2);
        result.relative_residual = std::sqrt(residual_norm2 / rhs_norm2);
    } else {
        result.converged = true;
    }
    const double* values = values_of(o.solution);
    std::copy(values, values + rows, solution);
    result.seconds = seconds_since(start);
    return result;
}

std::int64_t AmgPcg::local_rows() const { return static_cast<std::int64_t>(objects_->rows); }
double AmgPcg::copy_seconds() const { return objects_->copy_seconds; }
double AmgPcg::setup_seconds() const { return objects_->setup_seconds; }

HyprePcgResult solve_with_boomeramg(const SparseMatrix& matrix, const Eigen::VectorXd& rhs, double tolerance,
                                    int max_iterations)
{
    AmgPcg pcg(matrix, tolerance, max_iterations);
    HyprePcgResult result;
    result.solution.resize(matrix.rows());
    const PcgSolve solve = pcg.solve(rhs.data(), result.solution.data());
    result.iterations = solve.iterations;
    result.converged = solve.converged;
    result.copy_seconds = pcg.copy_seconds();
    result.setup_seconds = pcg.setup_seconds();
    result.iterate_seconds = solve.seconds;
    return result;
}

} // namespace tissuemesh::fem::detail

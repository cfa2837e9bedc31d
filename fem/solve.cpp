#include "fem/solve.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <string>

#include <Eigen/IterativeLinearSolvers>

#include "core/error.h"
#include "fem/detail/amg_processes.h"
#include "fem/detail/hypre_pcg.h"

namespace tissuemesh::fem {
namespace {

struct RawSolve {
    Eigen::VectorXd solution;
    int iterations = 0;
    double copy_seconds = 0, setup_seconds = 0, iterate_seconds = 0;
};

double seconds_since(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

RawSolve solve_jacobi(const SparseMatrix& matrix, const Eigen::VectorXd& rhs, const SolverOptions& options)
{
    // Lower|Upper: the full matrix is stored, so the product needs no symmetric reconstruction.
    Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper, Eigen::DiagonalPreconditioner<double>> cg;
    cg.setTolerance(options.relative_tolerance);
    cg.setMaxIterations(options.max_iterations);
    auto start = std::chrono::steady_clock::now();
    cg.compute(matrix);
    RawSolve result;
    result.setup_seconds = seconds_since(start);
    start = std::chrono::steady_clock::now();
    result.solution = cg.solve(rhs);
    result.iterate_seconds = seconds_since(start);
    result.iterations = static_cast<int>(cg.iterations());
    return result;
}

RawSolve solve_amg(const SparseMatrix& matrix, const Eigen::VectorXd& rhs, const SolverOptions& options,
                   const Progress& progress, int& processes)
{
    const int wanted = options.processes == 0 ? detail::available_cores() : std::max(options.processes, 1);
    const Eigen::Index share = std::max(options.min_unknowns_per_process, 1);
    processes = static_cast<int>(std::clamp<Eigen::Index>(matrix.rows() / share, 1, wanted));
    std::optional<detail::HyprePcgResult> amg;
    if (processes > 1) {
        std::string why_not;
        amg = detail::solve_on_processes(matrix, rhs, {.tolerance = options.relative_tolerance,
                                                       .max_iterations = options.max_iterations},
                                         {.processes = processes, .mpiexec = options.mpiexec}, why_not);
        if (!amg) {
            progress.warn("solve", concat("AMG-CG on ", processes, " processes failed (", why_not, "); solving in ",
                                          "one process instead"));
            processes = 1;
        }
    }
    if (!amg) amg = detail::solve_with_boomeramg(matrix, rhs, options.relative_tolerance, options.max_iterations);
    return {std::move(amg->solution), amg->iterations, amg->copy_seconds, amg->setup_seconds, amg->iterate_seconds};
}

} // namespace

Eigen::VectorXd solve_spd(const SparseMatrix& matrix, const Eigen::VectorXd& rhs, const SolverOptions& options,
                          const Progress& progress, SolverReport* report)
{
    const auto start = std::chrono::steady_clock::now();
    if (matrix.rows() != matrix.cols() || matrix.rows() != rhs.size())
        throw InputError(concat("linear system: matrix is ", matrix.rows(), " x ", matrix.cols(), " but the ",
                                "right-hand side has ", rhs.size(), " entries; they must agree"));
    if (!rhs.allFinite()) throw InputError("linear system: the right-hand side is not finite; check the sources");
    SolverReport local;
    local.preconditioner = options.preconditioner == Preconditioner::amg ? "amg" : "jacobi";
    const double rhs_norm = rhs.norm();
    Eigen::VectorXd solution = Eigen::VectorXd::Zero(rhs.size());
    if (rhs_norm > 0 && rhs.size() > 0) {
        RawSolve raw;
        if (options.preconditioner == Preconditioner::amg) {
            raw = solve_amg(matrix, rhs, options, progress, local.processes);
        } else {
            raw = solve_jacobi(matrix, rhs, options);
        }
        solution = std::move(raw.solution);
        local.iterations = raw.iterations;
        local.copy_seconds = raw.copy_seconds;
        local.setup_seconds = raw.setup_seconds;
        local.iterate_seconds = raw.iterate_seconds;
        local.relative_residual = (rhs - matrix * solution).norm() / rhs_norm;
    }
    local.seconds = seconds_since(start);
    progress.info("solve", concat(local.preconditioner, "-CG", local.processes > 1 ? concat(" on ", local.processes, " processes") : "",
                                  ": ", rhs.size(), " unknowns, ", local.iterations,
                                  " iterations, relative residual ", local.relative_residual));
    // The recomputed residual may sit slightly above the solver's own estimate (round-off in the
    // recurrence): allow a factor 10 before calling it a failure.
    if (!(local.relative_residual <= 10 * options.relative_tolerance))
        throw AlgorithmError(concat("linear system (", rhs.size(), " unknowns): ", local.preconditioner, "-CG reached ",
                                    "relative residual ", local.relative_residual, " after ", local.iterations,
                                    " iterations (tolerance ", options.relative_tolerance, ", cap ",
                                    options.max_iterations, "); raise the cap, use the amg preconditioner, or ",
                                    "improve the mesh (slivers slow CG down)"));
    if (report) *report = local;
    return solution;
}

} // namespace tissuemesh::fem

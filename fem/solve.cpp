#include "fem/solve.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <optional>
#include <string>

#include <Eigen/IterativeLinearSolvers>

#include "core/error.h"
#include "fem/detail/amg_processes.h"
#include "fem/detail/hypre_pcg.h"

namespace tissuemesh::fem {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::string format_duration(double seconds)
{
    if (seconds < 10) {
        char text[16];
        std::snprintf(text, sizeof text, "%.2f s", seconds);
        return text;
    }
    const auto whole = static_cast<long long>(std::llround(seconds));
    return whole < 60 ? concat(whole, " s") : concat(whole / 60, " min ", whole % 60, " s");
}

// Collects what each column cost, checks its residual, and reports progress: the fraction of columns done,
// and an info line at every tenth with the time per solve and the time left.
class ColumnLog {
public:
    ColumnLog(std::size_t columns, std::size_t rows, const SolverOptions& options, const Progress& progress,
              ColumnsReport& report)
        : columns_(columns), rows_(rows), options_(options), progress_(progress), report_(report)
    {
    }

    void solved(std::size_t k, int iterations, double relative_residual, double seconds)
    {
        // The recomputed residual may sit slightly above the solver's own estimate (round-off in the
        // recurrence): allow a factor 10 before calling it a failure.
        if (!(relative_residual <= 10 * options_.relative_tolerance))
            throw AlgorithmError(concat(
                "linear system (", rows_, " unknowns",
                columns_ > 1 ? concat(", right-hand side ", k + 1, " of ", columns_) : "",
                "): ", report_.preconditioner, "-CG reached relative residual ", relative_residual, " after ",
                iterations, " iterations (tolerance ", options_.relative_tolerance, ", cap ", options_.max_iterations,
                "); raise the cap, use the amg preconditioner, ", "or improve the mesh (slivers slow CG down)"));
        if (k == 0) {
            report_.min_iterations = report_.max_iterations = iterations;
            report_.max_relative_residual = 0;
            iterations_ = 0;
            later_seconds_ = 0;
            report_.first_solve_seconds = seconds;
        } else {
            later_seconds_ += seconds;
        }
        report_.min_iterations = std::min(report_.min_iterations, iterations);
        report_.max_iterations = std::max(report_.max_iterations, iterations);
        report_.max_relative_residual = std::max(report_.max_relative_residual, relative_residual);
        iterations_ += iterations;
        const std::size_t done = k + 1;
        report_.columns = done;
        report_.mean_iterations = static_cast<double>(iterations_) / static_cast<double>(done);
        report_.later_solve_seconds = done > 1 ? later_seconds_ / static_cast<double>(done - 1) : 0;
        progress_.update("solve", static_cast<double>(done) / static_cast<double>(columns_));
        if (columns_ >= 10 && done % (columns_ / 10) == 0 && done < columns_) {
            const double each = done > 1 ? report_.later_solve_seconds : seconds;
            progress_.info("solve",
                           concat(done, " of ", columns_, " solves done, ", format_duration(each), " each, about ",
                                  format_duration(each * static_cast<double>(columns_ - done)), " left"));
        }
    }

private:
    std::size_t columns_, rows_;
    const SolverOptions& options_;
    const Progress& progress_;
    ColumnsReport& report_;
    long long iterations_ = 0;
    double later_seconds_ = 0;
};

// The kept entries of x, in the order of kept_rows (all when empty).
const double* kept_of(const Eigen::VectorXd& x, const std::vector<std::uint32_t>& kept_rows,
                      std::vector<double>& buffer)
{
    if (kept_rows.empty()) return x.data();
    buffer.resize(kept_rows.size());
    for (std::size_t k = 0; k < kept_rows.size(); ++k) buffer[k] = x[kept_rows[k]];
    return buffer.data();
}

void fill_checked(const RhsFiller& rhs, std::size_t k, Eigen::VectorXd& b)
{
    b.setZero();
    rhs(k, b);
    if (!b.allFinite()) throw InputError("linear system: the right-hand side is not finite; check the sources");
}

void columns_jacobi(const SparseMatrix& matrix, std::size_t columns, const RhsFiller& rhs,
                    const std::vector<std::uint32_t>& kept_rows, const SolutionSink& sink, const SolverOptions& options,
                    ColumnLog& log, ColumnsReport& report)
{
    // Lower|Upper: the full matrix is stored, so the product needs no symmetric reconstruction.
    Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper, Eigen::DiagonalPreconditioner<double>> cg;
    cg.setTolerance(options.relative_tolerance);
    cg.setMaxIterations(options.max_iterations);
    auto start = Clock::now();
    cg.compute(matrix);
    report.setup_seconds = seconds_since(start);
    Eigen::VectorXd b(matrix.rows()), x;
    std::vector<double> buffer;
    for (std::size_t k = 0; k < columns; ++k) {
        fill_checked(rhs, k, b);
        start = Clock::now();
        const double b_norm = b.norm();
        x = b_norm > 0 ? Eigen::VectorXd(cg.solve(b)) : Eigen::VectorXd::Zero(b.size());
        const double residual = b_norm > 0 ? (b - matrix * x).norm() / b_norm : 0;
        log.solved(k, b_norm > 0 ? static_cast<int>(cg.iterations()) : 0, residual, seconds_since(start));
        sink(k, kept_of(x, kept_rows, buffer));
    }
}

void columns_amg_here(const SparseMatrix& matrix, std::size_t columns, const RhsFiller& rhs,
                      const std::vector<std::uint32_t>& kept_rows, const SolutionSink& sink,
                      const SolverOptions& options, ColumnLog& log, ColumnsReport& report)
{
    detail::AmgPcg pcg(matrix, options.relative_tolerance, options.max_iterations);
    report.copy_seconds = pcg.copy_seconds();
    report.setup_seconds = pcg.setup_seconds();
    Eigen::VectorXd b(matrix.rows()), x(matrix.rows());
    std::vector<double> buffer;
    for (std::size_t k = 0; k < columns; ++k) {
        fill_checked(rhs, k, b);
        const detail::PcgSolve solve = pcg.solve(b.data(), x.data());
        log.solved(k, solve.iterations, solve.relative_residual, solve.seconds);
        sink(k, kept_of(x, kept_rows, buffer));
    }
}

// On `processes` MPI processes; false (with a warning saying why) when they could not run.
bool columns_amg_on_processes(const SparseMatrix& matrix, std::size_t columns, const RhsFiller& rhs,
                              const std::vector<std::uint32_t>& kept_rows, const SolutionSink& sink,
                              const SolverOptions& options, int processes, const Progress& progress, ColumnLog& log,
                              ColumnsReport& report)
{
    std::string why_not;
    const auto start = Clock::now();
    bool handed_over = false;
    const detail::ColumnFiller filler = [&](std::size_t k, Eigen::VectorXd& b) { fill_checked(rhs, k, b); };
    const detail::ColumnSink receiver = [&](std::size_t k, const detail::PcgSolve& solve, const double* values) {
        if (!handed_over) report.prepare_seconds = seconds_since(start), handed_over = true;
        log.solved(k, solve.iterations, solve.relative_residual, solve.seconds);
        sink(k, values);
    };
    const std::optional<detail::ColumnsResult> result = detail::solve_columns_on_processes(
        matrix, columns, filler, kept_rows, receiver,
        {.tolerance = options.relative_tolerance, .max_iterations = options.max_iterations},
        {.processes = processes, .mpiexec = options.mpiexec}, why_not);
    if (!result) {
        progress.warn("solve", concat("AMG-CG on ", processes, " processes failed (", why_not, "); solving in ",
                                      "one process instead"));
        return false;
    }
    report.copy_seconds = result->copy_seconds;
    report.setup_seconds = result->setup_seconds;
    return true;
}

} // namespace

void solve_spd_columns(const SparseMatrix& matrix, std::size_t columns, const RhsFiller& rhs,
                       const std::vector<std::uint32_t>& kept_rows, const SolutionSink& sink,
                       const SolverOptions& options, const Progress& progress, ColumnsReport* report)
{
    const auto start = Clock::now();
    if (matrix.rows() != matrix.cols())
        throw InputError(
            concat("linear system: matrix is ", matrix.rows(), " x ", matrix.cols(), "; it must be square"));
    for (const std::uint32_t row : kept_rows)
        if (row >= matrix.rows())
            throw InputError(concat("linear system: kept row ", row, " is out of range (", matrix.rows(), " rows)"));
    ColumnsReport local;
    local.preconditioner = options.preconditioner == Preconditioner::amg ? "amg" : "jacobi";
    ColumnLog log(columns, static_cast<std::size_t>(matrix.rows()), options, progress, local);
    if (columns > 0 && matrix.rows() > 0) {
        if (options.preconditioner == Preconditioner::jacobi) {
            columns_jacobi(matrix, columns, rhs, kept_rows, sink, options, log, local);
        } else {
            const int wanted = options.processes == 0 ? detail::available_cores() : std::max(options.processes, 1);
            const Eigen::Index share = std::max(options.min_unknowns_per_process, 1);
            local.processes = static_cast<int>(std::clamp<Eigen::Index>(matrix.rows() / share, 1, wanted));
            if (local.processes > 1 && !columns_amg_on_processes(matrix, columns, rhs, kept_rows, sink, options,
                                                                 local.processes, progress, log, local))
                local.processes = 1;
            if (local.processes == 1) columns_amg_here(matrix, columns, rhs, kept_rows, sink, options, log, local);
        }
    }
    local.seconds = seconds_since(start);
    progress.info(
        "solve",
        concat(local.preconditioner, "-CG", local.processes > 1 ? concat(" on ", local.processes, " processes") : "",
               ": ", matrix.rows(), " unknowns, ", columns, columns == 1 ? " right-hand side, " : " right-hand sides, ",
               local.min_iterations == local.max_iterations ? concat(local.max_iterations)
                                                            : concat(local.min_iterations, "-", local.max_iterations),
               " iterations, relative residual up to ", local.max_relative_residual));
    if (report) *report = local;
}

Eigen::VectorXd solve_spd(const SparseMatrix& matrix, const Eigen::VectorXd& rhs, const SolverOptions& options,
                          const Progress& progress, SolverReport* report)
{
    const auto start = Clock::now();
    if (matrix.rows() != matrix.cols() || matrix.rows() != rhs.size())
        throw InputError(concat("linear system: matrix is ", matrix.rows(), " x ", matrix.cols(), " but the ",
                                "right-hand side has ", rhs.size(), " entries; they must agree"));
    if (!rhs.allFinite()) throw InputError("linear system: the right-hand side is not finite; check the sources");
    Eigen::VectorXd solution = Eigen::VectorXd::Zero(rhs.size());
    ColumnsReport columns;
    solve_spd_columns(
        matrix, 1, [&](std::size_t, Eigen::VectorXd& b) { b = rhs; }, {},
        [&](std::size_t, const double* values) { std::copy(values, values + rhs.size(), solution.data()); }, options,
        progress, &columns);
    SolverReport local;
    local.preconditioner = columns.preconditioner;
    local.processes = columns.processes;
    local.iterations = columns.max_iterations;
    const double rhs_norm = rhs.norm();
    local.relative_residual = rhs_norm > 0 ? (rhs - matrix * solution).norm() / rhs_norm : 0;
    local.copy_seconds = columns.copy_seconds;
    local.setup_seconds = columns.setup_seconds;
    local.iterate_seconds = columns.first_solve_seconds;
    local.seconds = seconds_since(start);
    if (report) *report = local;
    return solution;
}

} // namespace tissuemesh::fem

// The files through which tm-solve hands a linear system to the tm-amg-worker processes and gets the
// solution back (binary, this machine's byte order: both sides are the same build on the same machine).
#pragma once

#include <filesystem>

#include <Eigen/Core>

#include "fem/assemble.h"
#include "fem/detail/hypre_pcg.h"

namespace tissuemesh::fem::detail {

/// What the system file asks of the solver besides the system itself.
struct SolveRequest {
    double tolerance = 1e-10;  ///< relative residual to reach
    int max_iterations = 0;    ///< CG iteration cap
};

/// Writes A (square, compressed rows), b and the request to `path`.
/// @throws IoError when the file cannot be written
void write_system_file(const std::filesystem::path& path, const SparseMatrix& matrix, const Eigen::VectorXd& rhs,
                       const SolveRequest& request);

/// Reads block `part` of `parts` (consecutive rows, split evenly) of the system in `path`.
/// @throws IoError when the file is missing, truncated or not a system file
RowBlock read_row_block(const std::filesystem::path& path, int part, int parts, SolveRequest& request);

/// Writes the whole solution and the solver's counts (the solution of `result` holds every row).
/// @throws IoError when the file cannot be written
void write_result_file(const std::filesystem::path& path, const HyprePcgResult& result);

/// Reads a result file written for a system of `rows` rows.
/// @throws IoError when the file is missing, truncated, or for another size
HyprePcgResult read_result_file(const std::filesystem::path& path, std::int64_t rows);

} // namespace tissuemesh::fem::detail

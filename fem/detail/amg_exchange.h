// The files through which a solve hands a linear system and its right-hand sides to the tm-amg-worker
// processes and gets the solutions back (binary, this machine's byte order: both sides are the same build on
// the same machine). One system, any number of right-hand sides: the workers set BoomerAMG up once.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "fem/assemble.h"
#include "fem/detail/hypre_pcg.h"

namespace tissuemesh::fem::detail {

/// What the system file asks of the solver besides the system itself.
struct SolveRequest {
    double tolerance = 1e-10; ///< relative residual to reach
    int max_iterations = 0;   ///< CG iteration cap
};

struct CloseFile {
    void operator()(std::FILE* file) const { std::fclose(file); }
};
using FilePointer = std::unique_ptr<std::FILE, CloseFile>;

/// Writes a system file: A (square, compressed rows), the request, the rows whose solution values are wanted
/// back (all when `kept_rows` is empty), then `columns` right-hand sides through add_column().
class SystemFileWriter {
public:
    /// @throws IoError when the file cannot be written
    SystemFileWriter(const std::filesystem::path& path, const SparseMatrix& matrix, const SolveRequest& request,
                     std::int64_t columns, const std::vector<std::uint32_t>& kept_rows);
    /// Appends the next right-hand side (matrix.rows() entries; stored sparse when mostly zeros).
    void add_column(const Eigen::VectorXd& rhs);
    /// Closes the file after the last column. @throws IoError when a column is missing or the disk is full
    void finish();

private:
    std::filesystem::path path_;
    FilePointer file_;
    std::int64_t rows_ = 0, columns_ = 0, written_ = 0;
};

/// One worker's view of a system file: its block of rows (part of parts, consecutive, split evenly), the
/// request, the kept rows, and the right-hand sides one after another.
class SystemFileReader {
public:
    /// @throws IoError when the file is missing, truncated or not a system file
    SystemFileReader(const std::filesystem::path& path, int part, int parts);
    const RowBlock& block() const { return block_; }
    const SolveRequest& request() const { return request_; }
    std::int64_t columns() const { return columns_; }
    /// The kept rows (global, increasing); all rows when the file keeps all.
    const std::vector<std::int64_t>& kept_rows() const { return kept_; }
    /// This block's rows of the next right-hand side. @throws IoError when the file ends early
    void next_column(std::vector<double>& block_rhs);

private:
    std::filesystem::path path_;
    FilePointer file_;
    RowBlock block_;
    SolveRequest request_;
    std::int64_t columns_ = 0;
    std::vector<std::int64_t> kept_;
};

/// Writes a result file under a temporary name, a record per solved column as it comes (the caller reads
/// them while the workers go on), and renames it when every column is in.
class ResultFileWriter {
public:
    ResultFileWriter(const std::filesystem::path& path, std::int64_t columns, std::int64_t kept, double copy_seconds,
                     double setup_seconds);
    void add(const PcgSolve& solve, const std::vector<double>& kept_values);
    void finish();
    static std::filesystem::path partial_path(const std::filesystem::path& path);

private:
    std::filesystem::path path_;
    FilePointer file_;
};

/// Reads the records of a result file as they are written (from its temporary name, or the final one).
class ResultFileReader {
public:
    /// Opens the file when it exists; false while neither name exists yet.
    /// @throws IoError when it exists but is not a result file for `columns` columns of `kept` values
    bool open(const std::filesystem::path& path, std::int64_t columns, std::int64_t kept);
    bool is_open() const { return file_ != nullptr; }
    /// Reads the next record when the file holds it whole; false otherwise.
    bool next(PcgSolve& solve, std::vector<double>& kept_values);
    double copy_seconds() const { return copy_seconds_; }
    double setup_seconds() const { return setup_seconds_; }

private:
    std::filesystem::path path_;
    FilePointer file_;
    std::int64_t kept_ = 0;
    long long next_at_ = 0;
    double copy_seconds_ = 0, setup_seconds_ = 0;
};

} // namespace tissuemesh::fem::detail

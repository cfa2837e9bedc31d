#include "fem/detail/amg_exchange.h"

#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <string>

#include "core/error.h"

namespace tissuemesh::fem::detail {
namespace {

constexpr std::array<char, 8> system_magic{'T', 'M', 'A', 'M', 'G', 'S', 'Y', '2'};
constexpr std::array<char, 8> result_magic{'T', 'M', 'A', 'M', 'G', 'R', 'E', '2'};
// A result record: iterations, converged (int64), relative residual, seconds (double), then the kept values.
constexpr long long record_head_bytes = 4 * 8;
constexpr long long result_header_bytes = 8 + 2 * 8 + 2 * 8;

FilePointer open_file(const std::filesystem::path& path, const char* mode)
{
    FilePointer file(std::fopen(path.c_str(), mode));
    if (!file) throw IoError(concat(path.string(), ": cannot open (", std::strerror(errno), ")"));
    return file;
}

template <typename T>
void put(std::FILE* file, const std::filesystem::path& path, const T* data, std::size_t count)
{
    if (count > 0 && std::fwrite(data, sizeof(T), count, file) != count)
        throw IoError(concat(path.string(), ": write failed (disk full?)"));
}

template <typename T>
void get(std::FILE* file, const std::filesystem::path& path, T* data, std::size_t count)
{
    if (count > 0 && std::fread(data, sizeof(T), count, file) != count)
        throw IoError(concat(path.string(), ": truncated solver exchange file"));
}

void seek(std::FILE* file, const std::filesystem::path& path, long long offset)
{
    if (fseeko(file, static_cast<off_t>(offset), SEEK_SET) != 0)
        throw IoError(concat(path.string(), ": truncated solver exchange file"));
}

void check_magic(const std::array<char, 8>& magic, const std::filesystem::path& path,
                 const std::array<char, 8>& expected)
{
    if (magic != expected) throw IoError(concat(path.string(), ": not a solver exchange file of this version"));
}

void close(FilePointer file, const std::filesystem::path& path)
{
    if (std::fclose(file.release()) != 0) throw IoError(concat(path.string(), ": write failed (disk full?)"));
}

// Reads `bytes` at `offset` of an open file without moving any stream position (the file may still grow).
bool read_at(std::FILE* file, void* data, std::size_t bytes, long long offset)
{
    auto* at = static_cast<char*>(data);
    while (bytes > 0) {
        const ssize_t got = pread(fileno(file), at, bytes, static_cast<off_t>(offset));
        if (got <= 0) return false;
        at += got, offset += got, bytes -= static_cast<std::size_t>(got);
    }
    return true;
}

} // namespace

SystemFileWriter::SystemFileWriter(const std::filesystem::path& path, const SparseMatrix& matrix,
                                   const SolveRequest& request, std::int64_t columns,
                                   const std::vector<std::uint32_t>& kept_rows)
    : path_(path), file_(open_file(path, "wb")), rows_(matrix.rows()), columns_(columns)
{
    if (!matrix.isCompressed()) throw AlgorithmError("solver exchange: the matrix is not in compressed rows");
    const std::int64_t kept = kept_rows.empty() ? -1 : static_cast<std::int64_t>(kept_rows.size());
    const std::int64_t header[4] = {matrix.rows(), matrix.nonZeros(), columns, kept};
    const std::int64_t max_iterations = request.max_iterations;
    std::FILE* out = file_.get();
    put(out, path, system_magic.data(), system_magic.size());
    put(out, path, header, 4);
    put(out, path, &request.tolerance, 1);
    put(out, path, &max_iterations, 1);
    put(out, path, matrix.outerIndexPtr(), static_cast<std::size_t>(matrix.rows()) + 1);
    put(out, path, matrix.innerIndexPtr(), static_cast<std::size_t>(matrix.nonZeros()));
    put(out, path, matrix.valuePtr(), static_cast<std::size_t>(matrix.nonZeros()));
    put(out, path, kept_rows.data(), kept_rows.size());
}

void SystemFileWriter::add_column(const Eigen::VectorXd& rhs)
{
    std::vector<std::int32_t> indices;
    std::vector<double> values;
    for (Eigen::Index i = 0; i < rhs.size(); ++i)
        if (rhs[i] != 0) indices.push_back(static_cast<std::int32_t>(i)), values.push_back(rhs[i]);
    // Sparse (4 + 8 bytes an entry) while that is smaller than dense (8 bytes a row).
    const bool sparse = 12 * static_cast<std::int64_t>(indices.size()) < 8 * rows_;
    const std::int64_t entries = sparse ? static_cast<std::int64_t>(indices.size()) : -1;
    put(file_.get(), path_, &entries, 1);
    if (sparse) {
        put(file_.get(), path_, indices.data(), indices.size());
        put(file_.get(), path_, values.data(), values.size());
    } else {
        put(file_.get(), path_, rhs.data(), static_cast<std::size_t>(rhs.size()));
    }
    ++written_;
}

void SystemFileWriter::finish()
{
    if (written_ != columns_)
        throw AlgorithmError(concat("solver exchange: ", written_, " right-hand sides written of ", columns_));
    close(std::move(file_), path_);
}

SystemFileReader::SystemFileReader(const std::filesystem::path& path, int part, int parts)
    : path_(path), file_(open_file(path, "rb"))
{
    std::FILE* in = file_.get();
    std::array<char, 8> magic{};
    get(in, path, magic.data(), magic.size());
    check_magic(magic, path, system_magic);
    std::int64_t header[4] = {0, 0, 0, 0};
    std::int64_t max_iterations = 0;
    get(in, path, header, 4);
    get(in, path, &request_.tolerance, 1);
    get(in, path, &max_iterations, 1);
    const auto [rows, nonzeros, columns, kept] = header;
    if (rows <= 0 || rows > INT32_MAX || nonzeros < rows || parts <= 0 || part < 0 || part >= parts ||
        max_iterations <= 0 || columns < 0 || kept < -1 || kept > rows)
        throw IoError(concat(path.string(), ": inconsistent solver exchange header"));
    request_.max_iterations = static_cast<int>(max_iterations);
    columns_ = columns;
    const long long starts_at = 8 + 6 * 8;
    const long long columns_at = starts_at + 4 * (rows + 1);
    const long long values_at = columns_at + 4 * nonzeros;
    const long long kept_at = values_at + 8 * nonzeros;
    block_.global_rows = rows;
    block_.first_row = rows * part / parts;
    const std::int64_t last = rows * (part + 1) / parts;
    const auto count = static_cast<std::size_t>(last - block_.first_row);
    block_.starts.resize(count + 1);
    seek(in, path, starts_at + 4 * block_.first_row);
    get(in, path, block_.starts.data(), count + 1);
    const int offset = block_.starts.front();
    for (int& start : block_.starts) start -= offset;
    const auto entries = static_cast<std::size_t>(block_.starts.back());
    block_.columns.resize(entries);
    block_.values.resize(entries);
    seek(in, path, columns_at + 4LL * offset);
    get(in, path, block_.columns.data(), entries);
    seek(in, path, values_at + 8LL * offset);
    get(in, path, block_.values.data(), entries);
    for (int column : block_.columns)
        if (column < 0 || column >= rows) throw IoError(concat(path.string(), ": column ", column, " out of range"));
    seek(in, path, kept_at);
    if (kept < 0) {
        kept_.resize(static_cast<std::size_t>(rows));
        for (std::int64_t r = 0; r < rows; ++r) kept_[static_cast<std::size_t>(r)] = r;
    } else {
        std::vector<std::uint32_t> read(static_cast<std::size_t>(kept));
        get(in, path, read.data(), read.size());
        for (std::size_t k = 0; k < read.size(); ++k)
            if (read[k] >= rows || (k > 0 && read[k] <= read[k - 1]))
                throw IoError(concat(path.string(), ": kept rows not increasing or out of range"));
        kept_.assign(read.begin(), read.end());
    }
}

void SystemFileReader::next_column(std::vector<double>& block_rhs)
{
    std::FILE* in = file_.get();
    const auto first = block_.first_row;
    const auto count = block_.row_count();
    block_rhs.assign(static_cast<std::size_t>(count), 0.0);
    std::int64_t entries = 0;
    get(in, path_, &entries, 1);
    if (entries < 0) { // dense: skip to this block's rows
        const long long at = ftello(in);
        seek(in, path_, at + 8 * first);
        get(in, path_, block_rhs.data(), block_rhs.size());
        seek(in, path_, at + 8 * block_.global_rows);
        return;
    }
    if (entries > block_.global_rows) throw IoError(concat(path_.string(), ": inconsistent right-hand side"));
    std::vector<std::int32_t> indices(static_cast<std::size_t>(entries));
    std::vector<double> values(static_cast<std::size_t>(entries));
    get(in, path_, indices.data(), indices.size());
    get(in, path_, values.data(), values.size());
    for (std::size_t k = 0; k < indices.size(); ++k) {
        const std::int64_t row = indices[k];
        if (row < 0 || row >= block_.global_rows)
            throw IoError(concat(path_.string(), ": right-hand side row out of range"));
        if (row >= first && row < first + count) block_rhs[static_cast<std::size_t>(row - first)] = values[k];
    }
}

std::filesystem::path ResultFileWriter::partial_path(const std::filesystem::path& path)
{
    std::filesystem::path partial = path;
    partial += ".part";
    return partial;
}

ResultFileWriter::ResultFileWriter(const std::filesystem::path& path, std::int64_t columns, std::int64_t kept,
                                   double copy_seconds, double setup_seconds)
    : path_(path), file_(open_file(partial_path(path), "wb"))
{
    const std::int64_t counts[2] = {columns, kept};
    const double seconds[2] = {copy_seconds, setup_seconds};
    put(file_.get(), path_, result_magic.data(), result_magic.size());
    put(file_.get(), path_, counts, 2);
    put(file_.get(), path_, seconds, 2);
    std::fflush(file_.get());
}

void ResultFileWriter::add(const PcgSolve& solve, const std::vector<double>& kept_values)
{
    const std::int64_t counts[2] = {solve.iterations, solve.converged ? 1 : 0};
    const double figures[2] = {solve.relative_residual, solve.seconds};
    put(file_.get(), path_, counts, 2);
    put(file_.get(), path_, figures, 2);
    put(file_.get(), path_, kept_values.data(), kept_values.size());
    if (std::fflush(file_.get()) != 0) throw IoError(concat(path_.string(), ": write failed (disk full?)"));
}

void ResultFileWriter::finish()
{
    close(std::move(file_), path_);
    std::filesystem::rename(partial_path(path_), path_);
}

bool ResultFileReader::open(const std::filesystem::path& path, std::int64_t columns, std::int64_t kept)
{
    for (const std::filesystem::path& name : {ResultFileWriter::partial_path(path), path}) {
        std::FILE* file = std::fopen(name.c_str(), "rb");
        if (!file) continue;
        file_.reset(file);
        path_ = name;
        break;
    }
    if (!file_) return false;
    std::array<char, 8> magic{};
    std::int64_t counts[2] = {0, 0};
    double seconds[2] = {0, 0};
    // The header is written and flushed before the file is complete enough to matter; a header still on its
    // way reads as "not yet".
    if (!read_at(file_.get(), magic.data(), 8, 0) || !read_at(file_.get(), counts, sizeof counts, 8) ||
        !read_at(file_.get(), seconds, sizeof seconds, 24)) {
        file_.reset();
        return false;
    }
    check_magic(magic, path_, result_magic);
    if (counts[0] != columns || counts[1] != kept)
        throw IoError(
            concat(path_.string(), ": ", counts[0], " x ", counts[1], " solution values for ", columns, " x ", kept));
    kept_ = kept;
    copy_seconds_ = seconds[0];
    setup_seconds_ = seconds[1];
    next_at_ = result_header_bytes;
    return true;
}

bool ResultFileReader::next(PcgSolve& solve, std::vector<double>& kept_values)
{
    struct stat status {};
    if (fstat(fileno(file_.get()), &status) != 0) return false;
    const long long record = record_head_bytes + 8 * kept_;
    if (status.st_size < next_at_ + record) return false;
    std::int64_t counts[2] = {0, 0};
    double figures[2] = {0, 0};
    kept_values.resize(static_cast<std::size_t>(kept_));
    if (!read_at(file_.get(), counts, sizeof counts, next_at_) ||
        !read_at(file_.get(), figures, sizeof figures, next_at_ + 16) ||
        !read_at(file_.get(), kept_values.data(), kept_values.size() * 8, next_at_ + record_head_bytes))
        throw IoError(concat(path_.string(), ": truncated solver exchange file"));
    solve.iterations = static_cast<int>(counts[0]);
    solve.converged = counts[1] != 0;
    solve.relative_residual = figures[0];
    solve.seconds = figures[1];
    next_at_ += record;
    return true;
}

} // namespace tissuemesh::fem::detail

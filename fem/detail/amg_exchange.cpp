#include "fem/detail/amg_exchange.h"

#include <array>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "core/error.h"

namespace tissuemesh::fem::detail {
namespace {

constexpr std::array<char, 8> system_magic{'T', 'M', 'A', 'M', 'G', 'S', 'Y', '1'};
constexpr std::array<char, 8> result_magic{'T', 'M', 'A', 'M', 'G', 'R', 'E', '1'};

struct CloseFile {
    void operator()(std::FILE* file) const { std::fclose(file); }
};
using File = std::unique_ptr<std::FILE, CloseFile>;

File open_file(const std::filesystem::path& path, const char* mode)
{
    File file(std::fopen(path.c_str(), mode));
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

void check_magic(std::FILE* file, const std::filesystem::path& path, const std::array<char, 8>& expected)
{
    std::array<char, 8> magic{};
    get(file, path, magic.data(), magic.size());
    if (magic != expected) throw IoError(concat(path.string(), ": not a solver exchange file of this version"));
}

void close(File file, const std::filesystem::path& path)
{
    if (std::fclose(file.release()) != 0) throw IoError(concat(path.string(), ": write failed (disk full?)"));
}

} // namespace

void write_system_file(const std::filesystem::path& path, const SparseMatrix& matrix, const Eigen::VectorXd& rhs,
                       const SolveRequest& request)
{
    if (!matrix.isCompressed()) throw AlgorithmError("solver exchange: the matrix is not in compressed rows");
    File file = open_file(path, "wb");
    const std::int64_t header[2] = {matrix.rows(), matrix.nonZeros()};
    const std::int64_t max_iterations = request.max_iterations;
    put(file.get(), path, system_magic.data(), system_magic.size());
    put(file.get(), path, header, 2);
    put(file.get(), path, &request.tolerance, 1);
    put(file.get(), path, &max_iterations, 1);
    put(file.get(), path, matrix.outerIndexPtr(), static_cast<std::size_t>(matrix.rows()) + 1);
    put(file.get(), path, matrix.innerIndexPtr(), static_cast<std::size_t>(matrix.nonZeros()));
    put(file.get(), path, matrix.valuePtr(), static_cast<std::size_t>(matrix.nonZeros()));
    put(file.get(), path, rhs.data(), static_cast<std::size_t>(rhs.size()));
    close(std::move(file), path);
}

RowBlock read_row_block(const std::filesystem::path& path, int part, int parts, SolveRequest& request)
{
    File file = open_file(path, "rb");
    check_magic(file.get(), path, system_magic);
    std::int64_t header[2] = {0, 0};
    std::int64_t max_iterations = 0;
    get(file.get(), path, header, 2);
    get(file.get(), path, &request.tolerance, 1);
    get(file.get(), path, &max_iterations, 1);
    const auto [rows, nonzeros] = header;
    if (rows <= 0 || nonzeros < rows || parts <= 0 || part < 0 || part >= parts || max_iterations <= 0)
        throw IoError(concat(path.string(), ": inconsistent solver exchange header"));
    request.max_iterations = static_cast<int>(max_iterations);
    const long long starts_at = 8 + 4 * 8;
    const long long columns_at = starts_at + 4 * (rows + 1);
    const long long values_at = columns_at + 4 * nonzeros;
    const long long rhs_at = values_at + 8 * nonzeros;
    RowBlock block;
    block.global_rows = rows;
    block.first_row = rows * part / parts;
    const std::int64_t last = rows * (part + 1) / parts;
    const auto count = static_cast<std::size_t>(last - block.first_row);
    block.starts.resize(count + 1);
    seek(file.get(), path, starts_at + 4 * block.first_row);
    get(file.get(), path, block.starts.data(), count + 1);
    const int offset = block.starts.front();
    for (int& start : block.starts) start -= offset;
    const auto entries = static_cast<std::size_t>(block.starts.back());
    block.columns.resize(entries);
    block.values.resize(entries);
    block.rhs.resize(count);
    seek(file.get(), path, columns_at + 4LL * offset);
    get(file.get(), path, block.columns.data(), entries);
    seek(file.get(), path, values_at + 8LL * offset);
    get(file.get(), path, block.values.data(), entries);
    seek(file.get(), path, rhs_at + 8 * block.first_row);
    get(file.get(), path, block.rhs.data(), count);
    for (int column : block.columns)
        if (column < 0 || column >= rows) throw IoError(concat(path.string(), ": column ", column, " out of range"));
    return block;
}

void write_result_file(const std::filesystem::path& path, const HyprePcgResult& result)
{
    File file = open_file(path, "wb");
    const std::int64_t counts[3] = {result.solution.size(), result.iterations, result.converged ? 1 : 0};
    const double seconds[3] = {result.copy_seconds, result.setup_seconds, result.iterate_seconds};
    put(file.get(), path, result_magic.data(), result_magic.size());
    put(file.get(), path, counts, 3);
    put(file.get(), path, seconds, 3);
    put(file.get(), path, result.solution.data(), static_cast<std::size_t>(result.solution.size()));
    close(std::move(file), path);
}

HyprePcgResult read_result_file(const std::filesystem::path& path, std::int64_t rows)
{
    File file = open_file(path, "rb");
    check_magic(file.get(), path, result_magic);
    std::int64_t counts[3] = {0, 0, 0};
    double seconds[3] = {0, 0, 0};
    get(file.get(), path, counts, 3);
    get(file.get(), path, seconds, 3);
    if (counts[0] != rows) throw IoError(concat(path.string(), ": ", counts[0], " solution values for ", rows, " rows"));
    HyprePcgResult result;
    result.iterations = static_cast<int>(counts[1]);
    result.converged = counts[2] != 0;
    result.copy_seconds = seconds[0];
    result.setup_seconds = seconds[1];
    result.iterate_seconds = seconds[2];
    result.solution.resize(rows);
    get(file.get(), path, result.solution.data(), static_cast<std::size_t>(rows));
    return result;
}

} // namespace tissuemesh::fem::detail

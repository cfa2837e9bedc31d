#include "io/npy.h"

#include <bit>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <string_view>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/detail/csv_table.h"

namespace tissuemesh::io {
namespace {

static_assert(std::endian::native == std::endian::little, "the .npy writer stores this machine's doubles as '<f8'");

constexpr std::string_view magic{"\x93NUMPY", 6};
constexpr std::size_t max_header_bytes = 65536;

// The header dictionary of a version 1.0 file, padded with spaces to a multiple of 64 bytes with the
// preamble (magic, version, length) and ended by a newline, as NumPy writes it.
std::string header_for(std::size_t rows, std::size_t columns)
{
    std::string dictionary = concat("{'descr': '<f8', 'fortran_order': False, 'shape': (", rows, ", ", columns, "), }");
    const std::size_t preamble = magic.size() + 2 + 2;
    const std::size_t unpadded = preamble + dictionary.size() + 1;
    dictionary.append((64 - unpadded % 64) % 64, ' ');
    dictionary += '\n';
    return dictionary;
}

// A tiny reader for the Python literal NumPy writes: {'descr': '<f8', 'fortran_order': False, 'shape': (3, 4), }.
class Dictionary {
public:
    Dictionary(std::string_view text, const std::string& file) : text_(text), file_(file) {}

    std::string_view value_of(std::string_view key) const
    {
        const std::string quoted = concat("'", key, "'");
        const std::size_t at = text_.find(quoted);
        if (at == std::string_view::npos) fail(concat("the header has no '", key, "'"));
        std::size_t start = text_.find(':', at + quoted.size());
        if (start == std::string_view::npos) fail(concat("the header's '", key, "' has no value"));
        ++start;
        while (start < text_.size() && text_[start] == ' ') ++start;
        std::size_t end = start;
        if (end < text_.size() && text_[end] == '(') {
            end = text_.find(')', end);
            if (end == std::string_view::npos) fail("the header's shape is not closed");
            return text_.substr(start, end + 1 - start);
        }
        while (end < text_.size() && text_[end] != ',' && text_[end] != '}') ++end;
        return text_.substr(start, end - start);
    }

    [[noreturn]] void fail(const std::string& problem) const
    {
        throw IoError(concat(file_, ": ", problem, "; write the matrix with numpy.save (float64, 2-D)"));
    }

private:
    std::string_view text_;
    const std::string& file_;
};

// "(3, 4)" or "(5,)" -> dimensions; at most 2.
std::vector<std::size_t> parse_shape(std::string_view text, const Dictionary& dictionary)
{
    std::vector<std::size_t> shape;
    std::size_t at = 1;
    while (at + 1 < text.size()) {
        while (at < text.size() && (text[at] == ' ' || text[at] == ',')) ++at;
        if (at + 1 >= text.size()) break;
        std::size_t value = 0, digits = 0;
        while (at < text.size() && std::isdigit(static_cast<unsigned char>(text[at]))) {
            if (value > (std::numeric_limits<std::size_t>::max() - 9) / 10) dictionary.fail("a dimension is too large");
            value = value * 10 + static_cast<std::size_t>(text[at++] - '0');
            ++digits;
        }
        if (digits == 0)
            dictionary.fail(concat("the shape ", detail::printable(std::string(text)), " is not a tuple of sizes"));
        shape.push_back(value);
    }
    if (shape.empty() || shape.size() > 2)
        dictionary.fail(concat("the shape ", detail::printable(std::string(text)), " has ", shape.size(),
                               " dimensions, not 1 or 2"));
    return shape;
}

} // namespace

void write_npy(const std::filesystem::path& path, const NpyMatrix& matrix)
{
    if (matrix.values.size() != matrix.rows * matrix.columns)
        throw InputError(concat(path.string(), ": ", matrix.values.size(), " values for a ", matrix.rows, " x ",
                                matrix.columns, " matrix"));
    write_npy(path, matrix.rows, matrix.columns, matrix.values.data());
}

void write_npy(const std::filesystem::path& path, std::size_t rows, std::size_t columns, const double* values)
{
    const std::string header = header_for(rows, columns);
    write_stream_atomically(path, [&](std::ostream& out) {
        const auto length = static_cast<std::uint16_t>(header.size());
        const char preamble[4] = {1, 0, static_cast<char>(length & 0xff), static_cast<char>(length >> 8)};
        out.write(magic.data(), static_cast<std::streamsize>(magic.size()));
        out.write(preamble, 4);
        out.write(header.data(), static_cast<std::streamsize>(header.size()));
        out.write(reinterpret_cast<const char*>(values), static_cast<std::streamsize>(rows * columns * sizeof(double)));
    });
}

NpyMatrix read_npy(const std::filesystem::path& path)
{
    const std::string file = path.string();
    require_readable_file(path);
    std::ifstream in(path, std::ios::binary);
    char preamble[8] = {};
    if (!in.read(preamble, 8) || std::string_view(preamble, 6) != magic)
        throw IoError(concat(file, ": not a NumPy .npy file (no \\x93NUMPY magic); write it with numpy.save"));
    const int major = static_cast<unsigned char>(preamble[6]);
    std::size_t length = 0, preamble_size = 10;
    unsigned char bytes[4] = {};
    if (major == 1) {
        if (!in.read(reinterpret_cast<char*>(bytes), 2)) throw IoError(concat(file, ": truncated .npy header"));
        length = bytes[0] | static_cast<std::size_t>(bytes[1]) << 8;
    } else if (major == 2 || major == 3) {
        if (!in.read(reinterpret_cast<char*>(bytes), 4)) throw IoError(concat(file, ": truncated .npy header"));
        length = bytes[0] | static_cast<std::size_t>(bytes[1]) << 8 | static_cast<std::size_t>(bytes[2]) << 16 |
                 static_cast<std::size_t>(bytes[3]) << 24;
        preamble_size = 12;
    } else {
        throw IoError(concat(file, ": .npy format version ", major, " is not 1, 2 or 3"));
    }
    if (length > max_header_bytes)
        throw IoError(concat(file, ": a .npy header of ", length, " bytes; this is not a matrix file"));
    std::string header(length, '\0');
    if (!in.read(header.data(), static_cast<std::streamsize>(length)))
        throw IoError(concat(file, ": truncated .npy header"));
    const Dictionary dictionary(header, file);
    const std::string_view descr = dictionary.value_of("descr");
    if (descr != "'<f8'" && descr != "'float64'")
        dictionary.fail(
            concat("the values are ", detail::printable(std::string(descr)), ", not little-endian float64 ('<f8')"));
    const std::string_view order = dictionary.value_of("fortran_order");
    if (order != "False" && order != "True") dictionary.fail("fortran_order is neither True nor False");
    const std::vector<std::size_t> shape = parse_shape(dictionary.value_of("shape"), dictionary);
    NpyMatrix matrix;
    matrix.rows = shape[0];
    matrix.columns = shape.size() == 2 ? shape[1] : 1;
    std::error_code error;
    const std::uintmax_t size = std::filesystem::file_size(path, error);
    const std::size_t data_bytes = size - std::min<std::uintmax_t>(size, preamble_size + length);
    std::size_t count = 0, needed = 0; // rows * columns * 8 without overflow
    if (error || __builtin_mul_overflow(matrix.rows, matrix.columns, &count) ||
        __builtin_mul_overflow(count, 8, &needed) || needed != data_bytes)
        throw IoError(concat(file, ": the header says ", matrix.rows, " x ", matrix.columns,
                             " values but the file holds ", data_bytes,
                             " bytes of data; the file is truncated or not this matrix"));
    matrix.values.resize(matrix.rows * matrix.columns);
    if (!in.read(reinterpret_cast<char*>(matrix.values.data()), static_cast<std::streamsize>(data_bytes)))
        throw IoError(concat(file, ": truncated .npy data"));
    if (order == "True" && matrix.columns > 1) { // column-major on disk: transpose into C order
        std::vector<double> c_order(matrix.values.size());
        for (std::size_t r = 0; r < matrix.rows; ++r)
            for (std::size_t c = 0; c < matrix.columns; ++c)
                c_order[r * matrix.columns + c] = matrix.values[c * matrix.rows + r];
        matrix.values = std::move(c_order);
    }
    return matrix;
}

} // namespace tissuemesh::io

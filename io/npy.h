// NumPy .npy files of float64 matrices: what tm-leadfield writes and tm-solve reads back (lead fields).
#pragma once

#include <cstddef>
#include <filesystem>
#include <vector>

namespace tissuemesh::io {

/// A rows x columns matrix of doubles in C (row-major) order: values[r * columns + c].
struct NpyMatrix {
    std::size_t rows = 0, columns = 0;
    std::vector<double> values;
};

/// Writes `matrix` as a version 1.0 .npy file ('<f8', C order, shape (rows, columns)), atomically: the file
/// is complete or absent. NumPy reads it with numpy.load.
/// @throws InputError when values.size() != rows * columns
/// @throws IoError when the file cannot be written
void write_npy(const std::filesystem::path& path, const NpyMatrix& matrix);

/// The same from rows * columns values in C order (a lead field written straight from its buffer, no copy).
void write_npy(const std::filesystem::path& path, std::size_t rows, std::size_t columns, const double* values);

/// Reads a .npy file of little-endian float64 ('<f8'), shape (rows, columns) or (n,) (read as n x 1), in C or
/// Fortran order (versions 1.0 to 3.0 of the format). The file's size must match its header exactly; nothing
/// is allocated before that is checked.
/// @throws IoError naming the file and the problem (not .npy, another dtype, a shape of other rank, a size
///         that does not match, a header over 64 KiB)
NpyMatrix read_npy(const std::filesystem::path& path);

} // namespace tissuemesh::io

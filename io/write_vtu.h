// VTK XML unstructured grids (.vtu) of tet meshes with any number of point and cell arrays, for ParaView.
#pragma once

#include <filesystem>
#include <iterator>
#include <string>
#include <vector>

#include "core/tet_mesh.h"

namespace tissuemesh::io {

/// A named array attached to the points or the cells of a mesh: #entries x components values, row by row.
struct VtuArray {
    std::string name;           ///< with its unit where it has one ("E_V_per_m")
    std::vector<double> values; ///< entries * components values
    int components = 1;         ///< 1 (scalar) or 3 (vector)
    bool integer = false;       ///< written as Int64 instead of Float64
};

/// A scalar array from any range of numbers (one per point or cell).
template <typename Range>
VtuArray make_vtu_array(std::string name, const Range& values, bool integer = false)
{
    VtuArray array{std::move(name), {}, 1, integer};
    array.values.assign(std::begin(values), std::end(values));
    return array;
}

/// A 3-component array from one vector per point or cell.
inline VtuArray make_vtu_vectors(std::string name, const std::vector<Vec3>& vectors)
{
    VtuArray array{std::move(name), {}, 3, false};
    array.values.reserve(3 * vectors.size());
    for (const Vec3& v : vectors) array.values.insert(array.values.end(), v.begin(), v.end());
    return array;
}

/// How the arrays are stored: ASCII text, or zlib-compressed binary blocks in raw appended data (VTK's
/// vtkZLibDataCompressor with UInt64 headers; ParaView, VTK and meshio read both).
enum class VtuEncoding { ascii, compressed };

/// Writes `mesh` (points in mm) as a .vtu atomically: cell data "tissue" (the tet labels) followed by
/// `cell_arrays`, point data `point_arrays`. Non-finite values are written as +-1e30 (ParaView reads
/// no "inf").
/// @throws InputError when an array's size does not match the mesh; IoError when the file cannot be written
void write_vtu(const TetMesh& mesh, const std::filesystem::path& path, const std::vector<VtuArray>& point_arrays = {},
               const std::vector<VtuArray>& cell_arrays = {}, VtuEncoding encoding = VtuEncoding::ascii);

} // namespace tissuemesh::io

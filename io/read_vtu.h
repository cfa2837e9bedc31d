// Reading VTK XML unstructured grids (.vtu) of tetrahedra, with their point and cell arrays (a solved
// potential, field vectors, error volumes): what write_vtu() writes, and what ParaView, VTK and meshio write.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/tet_mesh.h"
#include "io/write_vtu.h"

namespace tissuemesh::io {

/// A .vtu as read: the mesh and its named arrays (the label array excepted).
struct VtuContent {
    TetMesh mesh;                       ///< tets positively oriented (a flipped tet's vertices swapped), no faces
    std::vector<VtuArray> point_arrays; ///< #points x components each, in file order
    std::vector<VtuArray> cell_arrays;  ///< #tets x components each, in file order
    std::string label_array;            ///< the cell array the tet labels came from ("" when none: labels 0)

    /// The point or cell array named `name`, or null.
    const VtuArray* point_array(const std::string& name) const;
    const VtuArray* cell_array(const std::string& name) const;
};

/// Reads a single-piece VTK XML UnstructuredGrid of tetrahedra (VTK cell type 10): ASCII, inline base64 or
/// appended (raw or base64) data, uncompressed or zlib-compressed, UInt32 or UInt64 headers, any integer or
/// float array type, little-endian. Tet labels come from the integer cell array "tissue" (ours), else
/// "gmsh:physical", "medit:ref" or "tetgen:ref" (meshio's names), else they are 0. Tissue names and
/// interface faces are not stored in .vtu files, so the mesh has none.
/// Every size is checked against the bytes that hold it before anything is allocated.
/// @throws IoError on unreadable, malformed, truncated or unsupported files (other cell types, several
///         pieces, big-endian, other compressors), InputError on dangling point indices or labels outside
///         0..65535; the message names the file, the problem and the fix
VtuContent read_vtu(const std::filesystem::path& path);

} // namespace tissuemesh::io

// Binary STL: geometry only, float32 coordinates, one record per triangle.
#pragma once

#include <ostream>
#include <string>

#include "core/interface_complex.h"

namespace tissuemesh::io::detail {

/// Writes the whole binary .stl file to `out` (normals from the vertex order, attribute 0).
void write_stl(const InterfaceComplex& complex, std::ostream& out);

/// Parses binary or ASCII .stl bytes (ASCII: starts with "solid" and its size is not that of a binary
/// file); corners with bit-identical coordinates become one vertex, every triangle gets the pair {1, 0}.
/// @throws IoError when a binary file's size does not match its triangle count, or ASCII is malformed
InterfaceComplex parse_stl(const std::string& bytes, const std::string& what);

} // namespace tissuemesh::io::detail

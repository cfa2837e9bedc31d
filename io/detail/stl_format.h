// STL: geometry only; binary (float32 coordinates, one record per triangle) or ASCII.
#pragma once

#include <ostream>
#include <string>

#include "core/interface_complex.h"

namespace tissuemesh::io::detail {

/// Writes the whole .stl file to `out`: binary (float32, attribute 0) or `ascii` ("%.9g": float32 exactly);
/// normals from the vertex order.
void write_stl(const InterfaceComplex& complex, std::ostream& out, bool ascii = false);

/// Parses binary or ASCII .stl bytes (ASCII: starts with "solid" and its size is not that of a binary
/// file); corners with bit-identical coordinates become one vertex, every triangle gets the pair {1, 0}.
/// @throws IoError when a binary file's size does not match its triangle count, or ASCII is malformed
InterfaceComplex parse_stl(const std::string& bytes, const std::string& what);

} // namespace tissuemesh::io::detail

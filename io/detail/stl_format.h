// Binary STL: geometry only, float32 coordinates, one record per triangle.
#pragma once

#include <string>

#include "core/interface_complex.h"

namespace tissuemesh::io::detail {

/// The whole binary .stl file (normals from the vertex order, attribute 0).
std::string format_stl(const InterfaceComplex& complex);

/// Parses binary .stl bytes; corners with bit-identical float coordinates become one vertex, every
/// triangle gets the pair {1, 0}.
/// @throws IoError when the size does not match the triangle count (truncated, or ascii STL)
InterfaceComplex parse_stl(const std::string& bytes, const std::string& what);

} // namespace tissuemesh::io::detail

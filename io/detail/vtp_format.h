// ParaView XML PolyData (.vtp, ascii) for interface complexes.
#pragma once

#include <ostream>
#include <string>

#include "core/interface_complex.h"

namespace tissuemesh::io::detail {

/// Writes the whole ascii .vtp file to `out`: points (Float64), triangles as Polys, cell data label_a and
/// label_b (UInt16: the triangle's `from` and `to`). Tissue names are not stored.
void write_vtp(const InterfaceComplex& complex, std::ostream& out);

/// Parses an ascii .vtp written by write_vtp() (or any ascii PolyData with triangle Polys; label_a and
/// label_b cell data optional, default {1, 0}).
/// @throws IoError when the file is not ascii VTK PolyData or is truncated or malformed
InterfaceComplex parse_vtp(const std::string& text, const std::string& what);

} // namespace tissuemesh::io::detail

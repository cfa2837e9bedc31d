// Object File Format (.off): geometry only.
#pragma once

#include <ostream>
#include <string>

#include "core/interface_complex.h"

namespace tissuemesh::io::detail {

/// Writes the whole .off file to `out` (ascii, coordinates with 17 significant digits).
void write_off(const InterfaceComplex& complex, std::ostream& out);

/// Parses .off text; every triangle gets the pair {1, 0}.
/// @throws IoError when the header is not OFF, the file is truncated, or a face is not a triangle
InterfaceComplex parse_off(const std::string& text, const std::string& what);

} // namespace tissuemesh::io::detail

// PLY for interface complexes: binary little-endian on write; ascii and binary (either endianness) on read.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "core/interface_complex.h"

namespace tissuemesh::io::detail {

/// Writes the whole PLY file for `complex` to `out`: vertex x, y, z (float64), face vertex_indices (uchar count, uint32
/// indices), label_a and label_b (ushort: the triangle's `from` and `to`), tissue names as
/// `comment tissue <label> <name>` and the background as `comment background <label>`, then each of
/// `comments` as a `comment` line.
void write_ply(const InterfaceComplex& complex, std::ostream& out, const std::vector<std::string>& comments = {});

/// Parses PLY `bytes`; `what` names the file in messages. Faces must be triangles; without label_a and
/// label_b every triangle gets {1, 0}. Other elements and properties are skipped.
/// @throws IoError when the file is not PLY, is truncated or malformed
InterfaceComplex parse_ply(const std::string& bytes, const std::string& what);

} // namespace tissuemesh::io::detail

// Wavefront .obj for interface complexes: `v` and `f` records; each run of triangles with one tissue pair
// under a group `g tissues_<from>_<to>`, so labels read back (other tools see one group per patch run).
#pragma once

#include <ostream>
#include <string>

#include "core/interface_complex.h"

namespace tissuemesh::io::detail {

/// Writes the whole .obj file to `out` (tissue names as `#` comments).
void write_obj(const InterfaceComplex& complex, std::ostream& out);

/// Parses .obj text: `v x y z [w]`, `f` with 3 vertices (`i`, `i/t`, `i//n`, `i/t/n`, negative = relative);
/// pairs from our groups, {1, 0} elsewhere; other records (vt, vn, usemtl, ...) are skipped.
/// @throws IoError on malformed data or faces that are not triangles, InputError on dangling indices
InterfaceComplex parse_obj(const std::string& text, const std::string& what);

} // namespace tissuemesh::io::detail

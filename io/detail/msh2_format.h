// Gmsh .msh 2.2, ASCII and binary: tets with physical = elementary = tissue label; faces with physical
// 1000 + from and elementary 1000 * from + to.
#pragma once

#include <string>

#include "core/tet_mesh.h"
#include "io/detail/byte_reader.h"

namespace tissuemesh::io::detail {

/// The whole file: faces first, then tets, numbered from 1; nodes 1..#V in vertex order.
std::string format_msh2(const TetMesh& mesh, bool binary);

/// Parses a 2.2 file (ASCII or binary), `in` positioned after the "$MeshFormat" line's version word
/// already checked by the caller: reads file type and data size, then every section. Elements other than
/// triangles and tets are skipped; tets come back positively oriented.
/// @throws IoError on malformed or truncated data, InputError on dangling node numbers
TetMesh parse_msh2(ByteReader& in);

} // namespace tissuemesh::io::detail

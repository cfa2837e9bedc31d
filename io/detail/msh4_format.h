// Gmsh .msh 4.1, ASCII and binary. Tets of tissue L lie in volume entity L with physical tag L; faces of
// pair {from, to} lie in surface entity 1000 * from + to with physical tag 1000 + from (the 2.2 layout,
// with the elementary tag as the entity).
#pragma once

#include <string>

#include "core/tet_mesh.h"
#include "io/detail/byte_reader.h"

namespace tissuemesh::io::detail {

/// The whole file: one element block per entity (faces by pair, then tets by tissue, each in mesh
/// order), nodes 1..#V in vertex order in one block.
std::string format_msh4(const TetMesh& mesh, bool binary);

/// Parses a 4.x file, `in` positioned after the version word: file type, data size, then every section.
/// Tet labels come from their volume's physical tag (the entity tag when it has none), face pairs from
/// the surface entity tag (1000 * from + to) or else {physical % 1000, 0}. Other element types are skipped.
/// @throws IoError on malformed or truncated data, InputError on dangling node numbers
TetMesh parse_msh4(ByteReader& in);

} // namespace tissuemesh::io::detail

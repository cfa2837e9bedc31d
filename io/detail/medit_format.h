// Medit (INRIA) ASCII .mesh: Tetrahedra with reference = tissue label, Triangles with reference =
// 1000 * from + to (the .msh face tag).
#pragma once

#include <string>

#include "core/tet_mesh.h"

namespace tissuemesh::io::detail {

/// The whole .mesh file (tissue names as `#` comments).
std::string format_medit(const TetMesh& mesh);

/// Parses .mesh text (also Edges, Quadrilaterals, Hexahedra, Corners, Ridges, ... from other tools, which
/// are skipped); tets come back positively oriented, names from our comments.
/// @throws IoError on malformed or truncated data
TetMesh parse_medit(const std::string& text, const std::string& what);

} // namespace tissuemesh::io::detail

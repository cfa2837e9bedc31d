// TetGen's .node/.ele/.face files: nodes, tets with the tissue label as region attribute, faces with the
// boundary marker 1000 * from + to (the .msh face tag).
#pragma once

#include <string>

#include "core/tet_mesh.h"

namespace tissuemesh::io::detail {

struct TetgenFiles {
    std::string node, ele, face; ///< the three files' contents (face may be empty when reading)
};

/// The three files, numbered from 1; tissue names as `#` comments in the .ele file.
TetgenFiles format_tetgen(const TetMesh& mesh);

/// Parses the files (numbering from 0 or 1, as the first node says; extra attributes and columns are
/// skipped; no .face: no faces); `what` is the base name for messages. Tets come back positively oriented.
/// @throws IoError on malformed or truncated data, InputError on dangling node numbers
TetMesh parse_tetgen(const TetgenFiles& files, const std::string& what);

} // namespace tissuemesh::io::detail

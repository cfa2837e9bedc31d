// Abaqus .inp: nodes and C3D4 tets, one element set per tissue (named after it, ending with its label:
// "scalp_1"), and the interface faces as element-face surfaces, one per tissue pair (abaqus_surfaces.h).
#pragma once

#include <string>

#include "core/tet_mesh.h"

namespace tissuemesh::io::detail {

/// The whole .inp file; each element set's label is recorded in a `**` comment so that it reads back.
/// @throws InputError (naming `what`) when a face is no face of a tet (see format_abaqus_surfaces)
std::string format_abaqus(const TetMesh& mesh, const std::string& what);

/// Parses *NODE, *ELEMENT (C3D4, C3D10 by their corners; other types skipped) and *ELSET (lists or
/// GENERATE). A tet's label comes from its element set: our comments, else the number the set's name ends
/// with, else the set's position (1, 2, ...); tets in no set get 0. Element sets that a *SURFACE uses are faces,
/// not tissues. *SURFACE, TYPE=ELEMENT gives faces (see add_abaqus_faces). Other keywords are skipped.
/// @throws IoError on malformed data, InputError on dangling node numbers
TetMesh parse_abaqus(const std::string& text, const std::string& what);

} // namespace tissuemesh::io::detail

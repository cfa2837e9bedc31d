// Rebuilding a tet mesh's interface and boundary faces from its tet labels.
#pragma once

#include "core/tet_mesh.h"

namespace tissuemesh::volume {

/// Replaces mesh.faces / mesh.face_sides by the faces the tet labels imply: every face between two tets
/// of different tissues, and every outer-boundary face (one tet). Sides follow tm-extract's convention:
/// between two tissues, `from` is the larger label and `to` the smaller, except that `background` is
/// always `to`; a boundary face has its tet's tissue as `from` and `background` as `to`. The face's
/// vertex order makes its normal point from `from` into `to` (out of the tet of tissue `from`).
/// Faces come in the order of their first tet (by index) and that tet's local faces: deterministic.
/// @pre  the mesh is conforming (a face has at most two tets) and tets are positively oriented
/// @throws InputError when indices are out of range or a face is shared by more than two tets
void mark_interfaces(TetMesh& mesh, Label background = 0);

} // namespace tissuemesh::volume

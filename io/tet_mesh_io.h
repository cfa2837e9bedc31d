// Reading and writing labelled tetrahedral meshes.
#pragma once

#include <filesystem>

#include "core/tet_mesh.h"

namespace tissuemesh::io {

/// Writes `mesh` atomically; the extension picks the format:
///  - `.msh`: Gmsh 2.2 ASCII, the layout SimNIBS and DUNEuro read: tetrahedra (type 4) with physical tag =
///    tissue label; interface and boundary triangles (type 2) with physical tag = 1000 + the label behind
///    the face (`from`) and elementary tag = 1000 * from + to (the face's normal points from `from` to
///    `to`); $PhysicalNames from the tissue names.
///  - `.mesh`: Medit (INRIA) ASCII: Tetrahedra with reference = label, Triangles with reference =
///    1000 * from + to.
///  - `.vtu`: VTK XML unstructured grid (ASCII) with cell data "tissue" (tets only).
/// @throws IoError when the file cannot be written or the extension is unknown
void write_tet_mesh(const TetMesh& mesh, const std::filesystem::path& path);

/// Reads a `.msh` (Gmsh 2.2 ASCII) or `.mesh` (Medit ASCII) written as above (or by other tools with the
/// same tag conventions: tets tagged with their tissue).
/// @throws IoError on unreadable or malformed files, InputError on dangling indices or NaN coordinates
TetMesh read_tet_mesh(const std::filesystem::path& path);

} // namespace tissuemesh::io

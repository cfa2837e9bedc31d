// Reading and writing labelled tetrahedral meshes.
#pragma once

#include <filesystem>

#include "core/tet_mesh.h"

namespace tissuemesh::io {

/// Gmsh .msh versions write_tet_mesh() can write.
enum class MshVersion { v2_2, v4_1 };

/// Variants of the formats that have them. Readers detect version and encoding from the file.
struct TetMeshWriteOptions {
    MshVersion msh_version = MshVersion::v2_2;  ///< .msh: 2.2 (SimNIBS, DUNEuro) or 4.1 (current Gmsh)
    bool binary = false;                        ///< .msh: binary instead of ASCII
    bool vtu_compressed = true;                 ///< .vtu: zlib-compressed binary (appended) instead of ASCII
};

/// Writes `mesh` atomically; the extension picks the format:
///  - `.msh`: Gmsh 2.2 (default) or 4.1, ASCII or binary, the layout SimNIBS and DUNEuro read: tetrahedra
///    with physical tag = tissue label; interface and boundary triangles with physical tag = 1000 + the
///    label behind the face (`from`) and elementary tag (4.1: surface entity) = 1000 * from + to (the
///    face's normal points from `from` to `to`); $PhysicalNames from the tissue names. 4.1 groups
///    elements by entity (faces by pair, tets by tissue; mesh order within each).
///  - `.mesh`: Medit (INRIA) ASCII: Tetrahedra with reference = label, Triangles with reference =
///    1000 * from + to.
///  - `.vtu`: VTK XML unstructured grid with cell data "tissue" (tets only).
///  - `.node` (or `.ele`): TetGen's `.node`, `.ele` (region attribute = label) and `.face` (marker =
///    1000 * from + to) next to each other, each written atomically.
///  - `.inp`: Abaqus, C3D4 tets in one element set per tissue; faces as element-face surfaces IF_<from>_<to>.
/// @throws IoError when the file cannot be written or the extension is unknown
void write_tet_mesh(const TetMesh& mesh, const std::filesystem::path& path, const TetMeshWriteOptions& options = {});

/// Reads any format write_tet_mesh() writes, whatever its version or encoding, and the same formats from
/// other tools (Gmsh, meshio, TetGen, ParaView): tets come back positively oriented, with the labels their
/// tags give (see each format), faces with their side pairs where the file has them (`.vtu`: no faces, no
/// names; its arrays: read_vtu()).
/// Every count is checked against the bytes that follow before anything is allocated.
/// @throws IoError on unreadable, malformed or truncated files, InputError on dangling indices or NaN
///         coordinates; the message names the file, the problem and the fix
TetMesh read_tet_mesh(const std::filesystem::path& path);

/// True when `path`'s extension is a tet mesh format (for tools that take either meshes or surfaces).
bool is_tet_mesh_path(const std::filesystem::path& path);

} // namespace tissuemesh::io

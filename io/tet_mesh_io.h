// Reading and writing labelled tetrahedral meshes.
#pragma once

#include <filesystem>
#include <map>

#include "core/tet_mesh.h"
#include "io/simnibs_tags.h"

namespace tissuemesh::io {

/// Gmsh .msh versions write_tet_mesh() can write.
enum class MshVersion { v2_2, v4_1 };

/// How a .msh numbers its tissues and faces.
enum class TissueNumbering {
    labels,  ///< ours: tets by label, faces 1000 + from and 1000 * from + to, $PhysicalNames from the names
    simnibs, ///< SimNIBS's: tets by SimNIBS tag (simnibs_tags()), faces as its mesher makes them, 2.2 binary
    duneuro, ///< DUNEuro's: 2.2 ASCII that dune-grid reads, tets only, tagged from an offset, conductivity file
};

/// Variants of the formats that have them. Readers detect version and encoding from the file.
struct TetMeshWriteOptions {
    MshVersion msh_version = MshVersion::v2_2;           ///< .msh: 2.2 (SimNIBS, DUNEuro) or 4.1 (current Gmsh)
    bool binary = false;                                 ///< .msh: binary instead of ASCII
    bool vtu_compressed = true;                          ///< .vtu: zlib-compressed binary (appended) instead of ASCII
    TissueNumbering numbering = TissueNumbering::labels; ///< .msh only; the others always carry labels
    SimnibsTagTable simnibs_table;                       ///< simnibs: the user's tags, beside the built-in names
    int duneuro_tag_offset = 1; ///< duneuro: the tag of the first tissue (DUNEuro's tensors.offset)
    std::map<Label, double> duneuro_conductivities_s_per_m; ///< duneuro: S/m of every tissue of the mesh
};

/// Writes `mesh` atomically; the extension picks the format:
///  - `.msh`: Gmsh 2.2 (default) or 4.1, ASCII or binary, the layout SimNIBS and DUNEuro read: tetrahedra
///    with physical tag = tissue label; interface and boundary triangles with physical tag = 1000 + the
///    label behind the face (`from`) and elementary tag (4.1: surface entity) = 1000 * from + to (the
///    face's normal points from `from` to `to`); $PhysicalNames from the tissue names. 4.1 groups
///    elements by entity (faces by pair, tets by tissue; mesh order within each).
///    With TissueNumbering::simnibs: Gmsh 2.2 binary whatever msh_version and binary say; tets tagged by
///    simnibs_tags(), faces rebuilt from the tets as SimNIBS's mesher makes them (detail/msh_layouts.h), both tags
///    equal. With TissueNumbering::duneuro: Gmsh 2.2 ASCII in the layout dune-grid's GmshReader reads ($Nodes right
///    after the format block, dense node numbers, tets only, names without spaces after $EndElements), tissue i
///    (ascending labels) tagged duneuro_tag_offset + i, and `<stem>.con` beside it: the conductivity of tissue i on
///    line i (DUNEuro's tensors.filename; set its tensors.offset to duneuro_tag_offset).
///  - `.mesh`: Medit (INRIA) ASCII: Tetrahedra with reference = label, Triangles with reference =
///    1000 * from + to.
///  - `.vtu`: VTK XML unstructured grid with cell data "tissue" (tets only).
///  - `.node` (or `.ele`): TetGen's `.node`, `.ele` (region attribute = label) and `.face` (marker =
///    1000 * from + to) next to each other, each written atomically.
///  - `.inp`: Abaqus, C3D4 tets in one element set per tissue; faces as element-face surfaces IF_<from>_<to>.
/// @throws IoError when the file cannot be written or the extension is unknown; InputError when a numbering
///         other than labels is asked for another format, or its tissues lack a tag or a conductivity
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

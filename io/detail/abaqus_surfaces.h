// Abaqus .inp interface faces as element-face surfaces: per tissue pair (from, to) a surface
// `*SURFACE, TYPE=ELEMENT, NAME=IF_<from>_<to>` listing, per C3D4 face id S1..S4, an element set
// `IF_<from>_<to>_S<k>_ELEMS` of the tets on the `from` side of the faces (on the `to` side when no tet of `from`
// has the face, e.g. for the outer boundary written as {0, tissue}). A `**` comment records the pair so that
// it reads back with its orientation; boundary conditions can be applied to the surfaces by name.
#pragma once

#include <array>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/tet_mesh.h"
#include "io/detail/byte_reader.h"

namespace tissuemesh::io::detail {

/// C3D4 face k (1..4) as the element's local corners, in Abaqus's order (S1: 1-2-3, S2: 1-4-2, S3: 2-4-3, S4: 3-4-1).
const std::array<std::size_t, 3>& c3d4_face(int k);

/// The comments, element sets and surfaces of `mesh`'s faces; `element_of_tet[t]` is tet t's element number.
/// @throws InputError (naming `what`) when a face is no face of a tet of one of its two tissues
std::string format_abaqus_surfaces(const TetMesh& mesh, const std::vector<long long>& element_of_tet,
                                   const std::string& what);

/// One *SURFACE of a file: its name, its lines (an element set name or an element number, and a face id 1..4).
struct AbaqusSurface {
    std::string name;
    std::vector<std::pair<std::string, int>> entries;
};

/// What the faces are built from: the surfaces, the element sets by name, element number -> tet, each tet's
/// corners in the file's order, and the pairs our comments give by surface name (upper case).
struct AbaqusFaceSources {
    const std::vector<AbaqusSurface>& surfaces;
    const std::vector<std::pair<std::string, std::vector<long long>>>& sets;
    const std::unordered_map<long long, std::size_t>& tet_of;
    const std::vector<Tet>& corners;
    const std::map<std::string, LabelPair>& pairs;
};

/// Adds a face to `mesh` for every surface entry: {from, to} from our comment (oriented from -> to), else
/// {the element's label, 0} (oriented out of the element). Entries naming no element or set of tets are an error.
/// @throws IoError (through `in`) on a face id outside 1..4 or an unknown element or set
void add_abaqus_faces(TetMesh& mesh, const AbaqusFaceSources& sources, const ByteReader& in);

} // namespace tissuemesh::io::detail

// Gmsh .msh 2.2, ASCII and binary: tets with physical = elementary = tissue label; faces with physical
// 1000 + from and elementary 1000 * from + to.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "core/tet_mesh.h"
#include "io/detail/byte_reader.h"

namespace tissuemesh::io::detail {

/// The elements of a 2.2 file with their tags as written: (physical, elementary) per face and per tet.
struct Msh2Elements {
    std::span<const Triangle> faces;
    std::vector<std::array<int, 2>> face_tags;
    std::span<const Tet> tets;
    std::vector<std::array<int, 2>> tet_tags;
    std::string physical_names;        ///< the whole $PhysicalNames section, or "" for none
    bool names_after_elements = false; ///< $PhysicalNames at the end (dune-grid's reader wants $Nodes first)
    std::vector<Triangle> owned_faces; ///< faces made for the file (`faces` then points here), else empty
};

/// The whole file: faces first, then tets, numbered from 1; nodes 1..#V in vertex order.
std::string format_msh2(const std::vector<Vec3>& vertices, const Msh2Elements& elements, bool binary);

/// Our layout: tets tagged by label, faces 1000 + from / 1000 * from + to, $PhysicalNames from the names.
std::string format_msh2(const TetMesh& mesh, bool binary);

/// Parses a 2.2 file (ASCII or binary), `in` positioned after the "$MeshFormat" line's version word
/// already checked by the caller: reads file type and data size, then every section. Elements other than
/// triangles and tets are skipped; tets come back positively oriented.
/// @throws IoError on malformed or truncated data, InputError on dangling node numbers
TetMesh parse_msh2(ByteReader& in);

} // namespace tissuemesh::io::detail

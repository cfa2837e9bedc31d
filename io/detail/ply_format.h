// PLY for interface complexes: binary little-endian on write; ascii and binary (either endianness) on read.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "core/interface_complex.h"

namespace tissuemesh::io::detail {

/// Writes the whole PLY file for `complex` to `out`, binary little-endian or `ascii`: vertex x, y, z (float64), face
/// vertex_indices (uint8 count, uint32 indices), label_a and label_b (uint16: the triangle's `from` and `to`), tissue
/// names as `comment tissue <label> <name>` and the background as `comment background <label>`, then each of
/// `comments` as a `comment` line. The type names are the sized ones (uint8, uint16, uint32): meshio's binary reader
/// knows no others for integers.
void write_ply(const InterfaceComplex& complex, std::ostream& out, const std::vector<std::string>& comments = {},
               bool ascii = false);

/// The header write_ply() puts before the data of a complex with these names, background, counts and extra
/// comment lines.
std::string ply_header(const TissueNames& names, Label background, std::size_t vertices, std::size_t triangles,
                       const std::vector<std::string>& comments = {}, bool ascii = false);

/// Appends one vertex (3 float64) or one face record (uint8 3, 3 uint32, uint16 from, uint16 to) as
/// write_ply() writes them.
void append_ply_vertex(std::string& out, const Vec3& vertex);
void append_ply_face(std::string& out, const Triangle& triangle, LabelPair side);

/// Parses PLY `bytes`; `what` names the file in messages. Faces must be triangles; without label_a and
/// label_b every triangle gets {1, 0}. Other elements and properties are skipped.
/// @throws IoError when the file is not PLY, is truncated or malformed
InterfaceComplex parse_ply(const std::string& bytes, const std::string& what);

} // namespace tissuemesh::io::detail

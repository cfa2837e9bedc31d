// What Gmsh .msh 2.2 and 4.1 share: the tag layout (SimNIBS/DUNEuro), $PhysicalNames, node numbering,
// element types, and little-endian binary output.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/tet_mesh.h"
#include "io/detail/byte_reader.h"

namespace tissuemesh::io::detail {

/// Elementary tag of a face: 1000 * from + to. Its physical tag is 1000 + from.
inline int face_tag(const LabelPair& pair) { return 1000 * pair.from + pair.to; }
inline int face_physical(const LabelPair& pair) { return 1000 + pair.from; }
/// The side pair of a face from its physical and elementary tags: ours (physical 1000 + from), else an
/// elementary tag of 1000 * from + to, else (foreign files) {physical, 0}.
LabelPair face_pair(int physical, int elementary);
/// The side pair of a face from a lone tag 1000 * from + to (Medit reference, TetGen marker).
LabelPair single_tag_pair(long long tag);

/// The $PhysicalNames section (names of tissues and of their boundary faces).
std::string format_physical_names(const TetMesh& mesh);
/// Parses the body of $PhysicalNames (after the keyword); volume names become tissue names.
void parse_physical_names(ByteReader& in, TissueNames& names);

/// Reads the rest of $MeshFormat after the version (file type, data size, byte-order mark) up to and with
/// $EndMeshFormat; returns whether the file is binary. `data_size_hint` says what an 8-byte data size means
/// for this version.
bool parse_mesh_format(ByteReader& in, const char* data_size_hint);

/// Gmsh node numbers -> vertex indices, dense or sparse.
class NodeIndex {
public:
    void reserve(std::size_t count) { tags_.reserve(count); }
    void add(long long tag) { tags_.push_back(tag); }
    /// Builds the lookup; throws when a node number repeats.
    void finish(const ByteReader& in);
    /// The vertex of node `tag`; throws InputError naming the file when there is none.
    std::uint32_t at(long long tag, const ByteReader& in) const;

private:
    std::vector<long long> tags_;
    std::vector<std::uint32_t> dense_;
    std::unordered_map<long long, std::uint32_t> sparse_;
};

/// Nodes of Gmsh element `type` (points, lines, triangles, quads, tets, hexes, prisms, pyramids and their
/// second-order kinds), or -1 for types we do not know.
int gmsh_element_nodes(int type);

/// Appends a tet of `label` to `mesh`, made positively oriented (swapping its last two vertices).
void add_tet(TetMesh& mesh, const std::array<std::uint32_t, 4>& v, Label label);

template <typename T>
void append_binary(std::string& out, T value)
{
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    out.append(bytes, sizeof(T));
}

/// "%.17g" of a coordinate.
void append_real(std::string& out, double value);

} // namespace tissuemesh::io::detail

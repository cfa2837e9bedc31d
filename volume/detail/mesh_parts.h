// Mesh parts: a tet mesh cut into disjoint sets of tets, each made a mesh of its own, edited on its own
// (in parallel) and put back. The rule that makes it safe: every node with a tet outside the part is frozen
// (the part's edits may neither move it nor split or flip a face or edge all of whose nodes are frozen). The
// faces a part shares with the rest have only such nodes, so they stay as they were and the merged mesh is
// conforming.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include <optional>

#include "core/node_tets.h"
#include "core/tet_mesh.h"
#include "volume/detail/face_map.h"

namespace tissuemesh::volume::detail {

inline constexpr std::uint32_t no_part = std::numeric_limits<std::uint32_t>::max();

/// One part as a mesh of its own.
struct MeshPart {
    TetMesh mesh;                         ///< the part's tets (ascending by index in the whole) over its own
                                          ///< nodes, and the whole's listed faces that are faces of its tets
    std::vector<std::uint32_t> from_node; ///< per part node: its index in the whole (ascending)
    std::vector<char> frozen;             ///< per part node: it has a tet outside the part
    std::vector<std::uint32_t> listed;    ///< the whole's listed faces in `mesh` (ascending indices)
};

/// The whole mesh's listed faces by vertex set, and the tets at each node: what cutting a mesh into parts needs.
class PartCutter {
public:
    explicit PartCutter(const TetMesh& whole);
    /// The part of the tets listed (ascending) in `tets`. Safe to call from several threads at once.
    MeshPart part(const std::vector<std::uint32_t>& tets) const;

private:
    /// The listed face with nodes {a, b, c}, if any (the first listed).
    std::optional<std::uint32_t> listed(std::uint32_t a, std::uint32_t b, std::uint32_t c) const;

    const TetMesh& whole_;
    /// The listed faces by their lowest node (compressed rows): the other two nodes, ascending, and the face.
    struct Listed {
        std::uint32_t middle, high, face;
    };
    std::vector<std::uint32_t> row_start_;
    std::vector<Listed> by_low_;
    std::vector<std::uint32_t> tets_at_; ///< per node: how many tets hold it
    std::vector<char> on_face_;          ///< per node: on a listed face
};

/// Tets cut into parts across one axis.
struct Cut {
    std::vector<std::uint32_t> part_of; ///< per tet: its part
    int axis = 0;
    std::vector<double> between; ///< per pair of neighbouring parts: where along the axis the cut between them lies
    /// The cut nearest to tet t's centroid.
    std::uint32_t nearest(const TetMesh& mesh, std::uint32_t t) const;
};

/// Cuts the tets into `count` parts across the longest side of the mesh's box, each holding about as many
/// tets (by their centroids). Depends only on the mesh and the count.
Cut cut_across(const TetMesh& mesh, std::size_t count);

/// The tets at each node of a mesh, to find the tets around others (built once for several questions).
class TetsAtNodes {
public:
    explicit TetsAtNodes(const TetMesh& mesh) : mesh_(mesh), at_(node_tets(mesh)) {}
    /// The tets flagged in `seeds` (per tet) and every tet within `rings` rings of them (through shared nodes),
    /// flagged per tet.
    std::vector<char> around(const std::vector<char>& seeds, std::size_t rings) const;

private:
    const TetMesh& mesh_;
    NodeTets at_;
};

/// TetsAtNodes(mesh).around(seeds, rings).
std::vector<char> tets_around(const TetMesh& mesh, const std::vector<char>& seeds, std::size_t rings);

/// Per tet flagged in `in`, the lowest index of the flagged tets connected to it through shared nodes flagged in
/// `through` (per node; every node when empty): its group. no_part for the others.
std::vector<std::uint32_t> groups_of(const TetMesh& mesh, const std::vector<char>& in,
                                     const std::vector<char>& through = {});

/// The whole with each part replaced by its edited mesh (`edited[k]`, over the part's nodes in its order, new
/// nodes after; the part's own `mesh` is not read and may have been moved into it): tets outside every part first (in
/// order), then each part's; the whole's listed faces outside every part, then each part's (a face two parts share
/// once). Frozen nodes are the same in all.
TetMesh merge_parts(const TetMesh& whole, const std::vector<std::uint32_t>& part_of, const std::vector<MeshPart>& parts,
                    const std::vector<TetMesh>& edited);

} // namespace tissuemesh::volume::detail

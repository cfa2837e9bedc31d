// The faces of a tet mesh and the tets on each side of them: the one face adjacency of the project (the FE
// face loops, the mesh check, interface marking and tetrahedralization's labelling read it).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/tet_mesh.h"

namespace tissuemesh {

/// No tet across a face.
inline constexpr std::uint32_t no_tet = 0xffffffffu;

/// Face adjacency of a list of tets. A face slot is 4 t + k: face k (opposite corner k, numbered as
/// tet_faces) of tet t.
class TetAdjacency {
public:
    /// The faces of `tets` (vertex indices < vertex_count; at most 2^30 tets). Runs on every core; the result
    /// does not depend on the thread count.
    TetAdjacency(const std::vector<Tet>& tets, std::size_t vertex_count);
    /// The same for TetGen's int tets (every index >= 0).
    TetAdjacency(const std::vector<std::array<int, 4>>& tets, std::size_t vertex_count);

    /// The tet across face k of tet t, or no_tet when t alone holds that face (the boundary). A face held by
    /// more than two tets (a non-conforming mesh) pairs its first two holders by slot; the others get no_tet.
    std::uint32_t across(std::size_t t, int k) const { return across_[4 * t + static_cast<std::size_t>(k)]; }
    /// How many tets hold face k of tet t: 1 on the boundary, 2 inside, more where the mesh is not conforming
    /// (counted up to 255).
    std::uint32_t holders(std::size_t t, int k) const { return holders_[4 * t + static_cast<std::size_t>(k)]; }

    /// A face of the mesh: its vertices ascending, how many tets hold it and the first two of them (by index;
    /// no_tet where there are fewer).
    struct Face {
        std::array<std::uint32_t, 3> vertices{};
        std::uint32_t holders = 0;
        std::array<std::uint32_t, 2> tets{no_tet, no_tet};
        std::size_t id = 0; ///< distinct per face, below id_count() (where its run of entries starts)
    };
    /// Every distinct face once, ascending by vertices.
    std::vector<Face> faces() const;
    /// The faces whose smallest vertex is v (< vertex_count()), ascending, each passed to visit(const Face&):
    /// faces() one bucket at a time, so that buckets can be visited side by side and nothing is stored.
    template <typename Visit>
    void for_each_face_at(std::uint32_t v, Visit&& visit) const
    {
        for (std::size_t e = start_[v]; e < start_[v + 1];) {
            const Face face = face_at(v, e);
            e += face.holders;
            visit(face);
        }
    }
    std::size_t vertex_count() const { return start_.empty() ? 0 : start_.size() - 1; }
    /// A bound on Face::id: ids index arrays of this size.
    std::size_t id_count() const { return entries_.size(); }
    /// The face with vertices {a, b, c} in any order (holders == 0 when no tet has it).
    Face find(std::uint32_t a, std::uint32_t b, std::uint32_t c) const;

private:
    template <typename TetList>
    void build(const TetList& tets, std::size_t vertex_count);

    std::vector<std::uint32_t> across_;
    std::vector<std::uint8_t> holders_;
    struct Entry {
        std::uint32_t middle, largest, slot;
    };
    /// Every slot bucketed by its face's smallest vertex (bucket v: entries_[start_[v] .. start_[v + 1])), inside a
    /// bucket sorted by (middle, largest vertex, slot), so a face's holders are consecutive.
    std::vector<std::size_t> start_;
    std::vector<Entry> entries_;
    /// The face of the run of entries from `first` (its smallest vertex v).
    Face face_at(std::uint32_t v, std::size_t first) const;
};

} // namespace tissuemesh

// EditableComplex: the state both complex editors (ComplexEditor, LocalEditor) edit, and the questions about
// connectivity they both ask of it. Triangle and vertex slots stay numbered while the editors work: a dead
// triangle keeps its slot (alive 0), a dead vertex has an empty star, new ones come after.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/interface_complex.h"
#include "surface/detail/edit_types.h"
#include "surface/detail/triangle_distance.h"

namespace tissuemesh::surface::detail {

class EditableComplex {
public:
    std::size_t vertex_slots() const { return positions_.size(); }
    std::size_t triangle_slots() const { return triangles_.size(); }
    std::size_t triangle_count() const { return alive_count_; }
    bool vertex_alive(std::uint32_t v) const { return !stars_[v].empty(); }
    bool triangle_alive(std::uint32_t t) const { return alive_[t] != 0; }
    const Vec3& position(std::uint32_t v) const { return positions_[v]; }
    const std::vector<Vec3>& positions() const { return positions_; }
    const Triangle& triangle(std::uint32_t t) const { return triangles_[t]; }
    const LabelPair& side(std::uint32_t t) const { return sides_[t]; }
    /// Alive triangles incident to v (unordered).
    const std::vector<std::uint32_t>& star(std::uint32_t v) const { return stars_[v]; }
    VertexKind kind(std::uint32_t v) const { return kinds_[v]; }
    /// The vertices whose kind the last collapse or split changed (the kept or new vertex and its neighbours
    /// are classified again).
    const std::vector<std::uint32_t>& reclassified() const { return reclassified_; }
    TriangleCorners corners(std::uint32_t t) const { return corners(triangles_[t]); }
    TriangleCorners corners(const Triangle& t) const { return {positions_[t[0]], positions_[t[1]], positions_[t[2]]}; }
    /// Mean edge length over alive triangles (first edges), mm; 1 when none is alive.
    double mean_edge_length() const;

    /// A vertex sharing an edge with v, and the number of alive triangles on that edge (3 or more: a
    /// junction edge).
    struct RingEntry {
        std::uint32_t vertex;
        std::uint32_t triangles;
    };
    /// The neighbours of v, in no particular order, each with its edge's multiplicity (into `out`, without
    /// allocating once `out` has grown): for loops that ask for neighbours and multiplicities of many vertices.
    void ring(std::uint32_t v, std::vector<RingEntry>& out) const;
    /// Vertices sharing an edge with v, ascending.
    std::vector<std::uint32_t> neighbours(std::uint32_t v) const;
    /// The neighbours of v across junction edges (two for a curve vertex), ascending.
    std::vector<std::uint32_t> curve_neighbours(std::uint32_t v) const;
    /// Number of alive triangles on edge vw (0: no such edge; 3 or more: a junction edge).
    std::uint32_t edge_multiplicity(std::uint32_t v, std::uint32_t w) const;
    /// The vertices opposite edge vw in the triangles on it (in the order of v's star), when exactly two
    /// triangles share it: the ends of the edge a flip of vw would make.
    std::optional<std::array<std::uint32_t, 2>> opposite_vertices(std::uint32_t v, std::uint32_t w) const;

    /// The alive triangles over every vertex slot (dead vertices kept, new ones after the original ones).
    InterfaceComplex snapshot() const;

protected:
    /// Takes the complex over, every triangle alive; the kinds are left to classify_all().
    explicit EditableComplex(InterfaceComplex&& complex);

    /// patch: one closed fan of one patch (every edge at v shared by two triangles of that patch); curve:
    /// exactly two junction edges, every other edge shared by two triangles; corner: anything else.
    VertexKind classify(std::uint32_t v) const;
    /// Classifies every vertex (once the triangles are as the editor keeps them).
    void classify_all();
    /// Classifies v and `others` again (every neighbour of v when not given), recording changes in
    /// reclassified_.
    void reclassify(std::uint32_t v, const std::vector<std::uint32_t>* others = nullptr);

    Label background_ = 0;
    TissueNames names_;
    std::vector<Vec3> positions_;
    std::vector<Triangle> triangles_;
    std::vector<LabelPair> sides_;
    std::vector<char> alive_;
    std::vector<std::vector<std::uint32_t>> stars_;
    std::vector<VertexKind> kinds_;
    std::vector<std::uint32_t> reclassified_; ///< see reclassified()
    std::size_t alive_count_ = 0;             ///< alive triangles

private:
    // Scratch of classify() and reclassify(), kept between calls (edits ask them millions of times). The
    // const questions above keep none: smoothing asks them from several threads at once.
    mutable std::vector<RingEntry> classify_ring_;
    std::vector<RingEntry> reclassify_ring_;
};

} // namespace tissuemesh::surface::detail

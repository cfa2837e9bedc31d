// WorkMesh: a tet mesh the improver edits in place: tets with their tissues, each node's tets and
// constraint faces, and a journal of every edit so that a trial can be undone exactly.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "core/tet_mesh.h"
#include "volume/detail/tet_quality.h"

namespace tissuemesh::volume::detail {

/// Where a node may go: anywhere (inside a tissue), on its interface patch, along its junction curve
/// (where three or more patches meet), or nowhere (corners of curves, and every odd place).
enum class NodeKind : std::uint8_t { interior, surface, curve, corner };

/// A face no edit may remove: an interface or outer-boundary face. Corners ordered so that the normal
/// points from sides.from into sides.to.
struct ConstraintFace {
    Triangle corners{};
    LabelPair sides;
    bool listed = true; ///< one of the mesh's faces (false: implied by the tissues or the outer boundary only)
    bool alive = true;
};

class WorkMesh {
public:
    /// The mesh's tets, and as constraint faces its listed faces plus every face between two tissues and
    /// every outer-boundary face. Nodes flagged in `frozen` (per node; empty: none) are corners whatever their
    /// faces: the nodes of a mesh part that have tets outside it (mesh_parts.h), whose faces no edit may change.
    /// @pre tets positively oriented, conforming
    explicit WorkMesh(const TetMesh& mesh, std::vector<char> frozen = {});

    /// The mesh now: alive tets in slot order, every node (new ones after the old), the listed faces.
    TetMesh result() const;

    // ---- nodes
    std::size_t node_count() const { return points_.size(); }
    const Vec3& point(std::uint32_t v) const { return points_[v]; }
    const std::vector<Vec3>& points() const { return points_; }
    NodeKind kind(std::uint32_t v) const { return kinds_[v]; }
    /// Whether v is frozen: it never moves, and no edit may split or flip a face or edge all of whose nodes
    /// are frozen (they may lie on a face shared with another part).
    bool frozen(std::uint32_t v) const { return v < frozen_.size() && frozen_[v] != 0; }
    /// The local size at v: for the mesh's own nodes their shortest edge on entry, for new nodes what
    /// set_scale() gave them (infinity until then). Insertion keeps new nodes a fraction of it apart.
    double scale(std::uint32_t v) const { return scales_[v]; }
    /// Sets the scale of a node added since the last commit (undone with it).
    void set_scale(std::uint32_t v, double scale) { scales_[v] = scale; }
    const std::vector<std::uint32_t>& tets_of(std::uint32_t v) const { return tets_of_[v]; }
    const std::vector<std::uint32_t>& faces_of(std::uint32_t v) const { return faces_of_[v]; }
    /// The tissues of the constraint faces at v, ascending (empty for interior nodes).
    std::vector<Label> tissues_at(std::uint32_t v) const;
    /// The other ends of the junction edges at v (edges with three or more constraint faces).
    std::vector<std::uint32_t> curve_neighbours(std::uint32_t v) const;

    // ---- tets (slots; a removed tet's slot is reused after the edit that removed it is committed)
    std::size_t tet_slots() const { return tets_.size(); }
    std::size_t tet_count() const { return alive_count_; }
    bool alive(std::uint32_t t) const { return alive_[t] != 0; }
    const Tet& tet(std::uint32_t t) const { return tets_[t]; }
    Label label(std::uint32_t t) const { return labels_[t]; }
    double quality(std::uint32_t t) const { return quality_[t]; } ///< min_sine(), cached
    /// Volume (mm^3) of each tissue's alive tets, kept up to date by every edit and its undoing.
    const std::map<Label, double>& tissue_volumes() const { return tissue_volumes_; }
    std::uint32_t stamp(std::uint32_t t) const { return stamps_[t]; } ///< changes whenever the tet or its shape does
    std::uint32_t birth(std::uint32_t t) const { return births_[t]; } ///< changes whenever the slot gets a tet
    TetCorners corners(std::uint32_t t) const;
    TetCorners corners(const Tet& tet) const;

    // ---- constraint faces
    const ConstraintFace& face(std::uint32_t f) const { return faces_[f]; }
    std::size_t face_slots() const { return faces_.size(); } ///< alive faces and removed ones
    /// The constraint faces on the outer boundary (one tet) when the mesh was built, ascending.
    const std::vector<std::uint32_t>& outer_faces_at_start() const { return outer_at_start_; }
    std::optional<std::uint32_t> face_with(std::uint32_t a, std::uint32_t b, std::uint32_t c) const;
    /// Whether any constraint face holds edge ab.
    bool constrained_edge(std::uint32_t a, std::uint32_t b) const;

    // ---- adjacency
    bool has_edge(std::uint32_t a, std::uint32_t b) const;
    void tets_of_edge(std::uint32_t a, std::uint32_t b, std::vector<std::uint32_t>& out) const;
    /// The alive tet with these four nodes, if any.
    std::optional<std::uint32_t> tet_with(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) const;
    /// The tet across the face of t opposite its corner i, if any.
    std::optional<std::uint32_t> tet_across(std::uint32_t t, int i) const;
    /// The ring around edge ab: ring[i], ring[i+1] (cyclically) with a and b make tets[i], and (a, b, ring[i],
    /// ring[i+1]) is positively oriented. With `open` null only closed rings count (false for an edge on the outer
    /// boundary); else an open chain is accepted too (ring then has one node more than tets) and *open says which.
    bool edge_ring(std::uint32_t a, std::uint32_t b, std::vector<std::uint32_t>& ring, std::vector<std::uint32_t>& tets,
                   bool* open = nullptr) const;

    // ---- edits, journaled
    std::uint32_t add_tet(const Tet& tet, Label label);
    void remove_tet(std::uint32_t t);
    void move_node(std::uint32_t v, const Vec3& p);
    std::uint32_t add_node(const Vec3& p);
    std::uint32_t add_face(const Triangle& corners, LabelPair sides, bool listed);
    void remove_face(std::uint32_t f);
    /// Recomputes the kind of v from its constraint faces (after face edits).
    void classify(std::uint32_t v);

    /// The journal's length now, to roll back to.
    std::size_t mark() const { return journal_.size(); }
    /// Undoes every edit after `mark`, newest first.
    void rollback(std::size_t mark);
    /// Keeps every edit: the journal is emptied and removed tets' slots become free.
    void commit();
    /// Tets added or reshaped since the last call (alive or not; some repeated).
    std::vector<std::uint32_t> take_touched();
    /// Whether every alive tet the edits since `mark` added or reshaped has a volume within bound(its label).
    template <class Bound>
    bool changed_tets_within(std::size_t mark, const Bound& bound) const
    {
        const auto within = [&](std::uint32_t t) { return !alive_[t] || volume_[t] <= bound(labels_[t]); };
        for (std::size_t i = mark; i < journal_.size(); ++i) {
            const Entry& e = journal_[i];
            if (e.change == Change::tet_added && !within(e.index)) return false;
            if (e.change == Change::node_moved)
                for (const std::uint32_t t : tets_of_[e.index])
                    if (!within(t)) return false;
        }
        return true;
    }

    /// What the edits since `mark` did to the quality: the worst min_sine() of the tets they removed that were
    /// there at `mark` (before), and of the alive tets they added or reshaped (after). Node moves are taken as
    /// moves of new nodes or of nodes whose tets are all new (true of every trial the improver makes).
    struct Balance {
        double before, after;
    };
    Balance balance_since(std::size_t mark) const;

    /// The constraint faces the edits since `mark` changed: in `before` as they were at `mark` (those removed and
    /// those at moved nodes, with the nodes where they were), in `after` as they are now (those added and those
    /// at moved nodes). Together they bound the region the interfaces swept (at a junction-curve node, one region
    /// between each patch's faces before and after).
    void swept_faces(std::size_t mark, std::vector<std::array<Vec3, 3>>& before,
                     std::vector<std::array<Vec3, 3>>& after) const;
    /// The alive constraint faces the edits since `mark` added or moved (a node of theirs moved), ascending.
    void faces_changed_since(std::size_t mark, std::vector<std::uint32_t>& out) const;
    /// How many alive tets hold face abc (1 on the outer boundary, 2 inside).
    int holders(std::uint32_t a, std::uint32_t b, std::uint32_t c) const;

private:
    enum class Change : std::uint8_t {
        tet_added,
        tet_removed,
        node_moved,
        node_added,
        face_added,
        face_removed,
        kind_set
    };
    struct Entry {
        Change change;
        std::uint32_t index;
        Vec3 point{};
        NodeKind kind = NodeKind::interior;
        std::uint32_t birth = 0; ///< a removed tet's birth, restored when it comes back
    };

    NodeKind compute_kind(std::uint32_t v) const;
    void link_tet(std::uint32_t t);
    void unlink_tet(std::uint32_t t);
    void link_face(std::uint32_t f);
    void unlink_face(std::uint32_t f);
    void refresh_quality(std::uint32_t t);

    std::vector<Vec3> points_;
    std::vector<NodeKind> kinds_;
    std::vector<char> frozen_;
    std::vector<double> scales_;
    std::vector<std::vector<std::uint32_t>> tets_of_, faces_of_;
    std::vector<Tet> tets_;
    std::vector<Label> labels_;
    std::vector<std::uint8_t> alive_;
    std::vector<double> quality_, volume_;
    std::map<Label, double> tissue_volumes_;
    std::vector<std::uint32_t> stamps_, births_;
    std::size_t alive_count_ = 0;
    std::vector<std::uint32_t> free_slots_, freed_now_;
    std::vector<ConstraintFace> faces_;
    std::vector<std::uint32_t> outer_at_start_;
    TissueNames names_;
    std::vector<Entry> journal_;
    std::vector<std::uint32_t> touched_;
};

} // namespace tissuemesh::volume::detail

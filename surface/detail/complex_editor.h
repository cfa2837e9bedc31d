// ComplexEditor: local edits of an interface complex (move, collapse, split, flip), each accepted only
// when the complex stays valid. The engine of smooth(), repair() and snake() (decimate() and remesh() use
// LocalEditor, local_editor.h; both edit an EditableComplex).
//
// Why our own structure and not OpenMesh's half-edges: an interface complex is not a 2-manifold. Along
// junction curves three or more triangles share an edge, which a half-edge mesh cannot hold, and
// decimating each patch on its own could not collapse a junction edge in all patches at once.
//
// Validity of every edit is decided locally, where it happens:
//  - topology: a collapse must satisfy the link condition Lk(v) n Lk(w) = Lk(vw) (Dey, Edelsbrunner,
//    Guha, Nekhayev 1999), which keeps the topological type of the whole 2-complex, junctions included;
//    vertices on a junction curve move and collapse only along their curve, curve corners never change;
//  - geometry: no changed triangle is degenerate (exact test), gets a smaller angle than both its old one
//    and EditLimits::min_angle_deg, tilts by more than EditLimits::max_normal_change_deg, or meets any
//    other triangle other than at shared vertices and edges (exact predicates, candidates from a grid);
//    and none comes closer than EditLimits::min_gap_mm to a triangle it shares no vertex with, unless it
//    was already that close (so thin layers keep a positive thickness); around every junction edge the
//    triangles keep an order their tissues agree with (edge_fan.h: no pocket turns inside out).
// So an edit sequence applied to a complex that passes check_complex() yields one that passes it too.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/interface_complex.h"
#include "surface/detail/box_index.h"
#include "surface/detail/edit_types.h"
#include "surface/detail/editable_complex.h"
#include "surface/detail/edge_fan.h"
#include "surface/detail/angle_limit.h"
#include "surface/detail/triangle_grid.h"

namespace tissuemesh::surface::detail {

/// Geometric limits every edit must respect. Lengths in mm, angles in degrees.
struct EditLimits {
    double min_angle_deg = 2.0;          ///< new triangles' smallest angle (unless not worse than before)
    double max_normal_change_deg = 60.0; ///< a changed triangle may tilt at most this much in one edit
    double min_gap_mm = 0.0;             ///< distance kept between triangles sharing no vertex
    double min_wedge_deg = 1.0;          ///< opening kept between triangles sharing one vertex (see
                                         ///< wedge_angle.h), unless not thinner than before
    /// For repair(): an edit may leave intersections that were already there, as long as the changed
    /// triangles meet no more other triangles than before the edit (never more; none when there were none).
    /// The order around junction edges is then not judged per edit (a crossing tangles the junctions it
    /// passes, and undoing it may pass through tangles); repair() checks the whole at the end.
    bool tolerate_existing_intersections = false;
};

class ComplexEditor : public EditableComplex {
public:
    /// Takes the complex over. Patches are oriented canonically (the larger label is `from`, the
    /// background always `to`), which does not change what the triangles mean.
    /// `cell_mm`: grid cell size for neighbour searches (about twice the typical edge length).
    ComplexEditor(InterfaceComplex complex, const EditLimits& limits, double cell_mm);

    // --- reading: EditableComplex ---
    const EditLimits& limits() const { return limits_; }
    void set_limits(const EditLimits& limits)
    {
        limits_ = limits;
        min_angle_ = AngleLimit(limits.min_angle_deg);
        max_tilt_ = AngleLimit(limits.max_normal_change_deg);
    }
    const EditCounters& counters() const { return counters_; }

    // --- editing: each returns whether the edit was made; a refused edit changes nothing ---
    /// Moves v to p (junction-curve and corner rules are the caller's business: see VertexKind).
    bool try_move(std::uint32_t v, const Vec3& p);
    /// Moves every vertices[i] to positions[i] in one edit (all or none), for regions that must move together.
    bool try_move_group(const std::vector<std::uint32_t>& vertices, const std::vector<Vec3>& positions);
    /// Moves every vertices[i] (distinct) to targets[i] at once and keeps as many of the moves as it can:
    /// the changed triangles are judged together (in parallel, by the rules of try_move()), the moved
    /// vertices of every offending triangle and of the triangles it meets or crowds go back to where they
    /// were, and the triangles around those are judged again, until none offends. The outcome depends only
    /// on the input (not on thread count or scheduling). Returns, per entry, whether the vertex moved.
    /// @pre not in tolerant mode (EditLimits::tolerate_existing_intersections false)
    std::vector<char> move_together(const std::vector<std::uint32_t>& vertices, const std::vector<Vec3>& targets);
    /// Collapses edge vw into w: v disappears, w keeps its position. `veto`, when given, is asked after
    /// the cheap local checks (topology, shape, tilt) and before the costly ones (intersection, gap):
    /// false refuses the collapse (counted by the caller, not in counters()).
    bool try_collapse(std::uint32_t v, std::uint32_t w, const std::function<bool()>& veto = {});
    /// Splits edge vw (every triangle on it) at p; returns the new vertex.
    std::optional<std::uint32_t> try_split(std::uint32_t v, std::uint32_t w, const Vec3& p);
    /// Replaces edge vw (two triangles of one patch) by the edge between their opposite vertices.
    bool try_flip(std::uint32_t v, std::uint32_t w);
    /// Rebuilds the neighbour grid with a new cell size (after triangles grew or shrank a lot). The grid
    /// is built when an edit first needs it.
    void rebuild_grid(double cell_mm);

    /// The edited complex, compacted (dead vertices and triangles dropped, order otherwise kept).
    InterfaceComplex result() const;

private:
    struct Change {
        std::uint32_t slot;     ///< triangle slot it replaces (or a new slot)
        Triangle triangle;      ///< new vertex indices
        TriangleCorners before; ///< geometry of the triangle it replaces, for the "not worse" rules
        LabelPair side{};       ///< tissues of a new slot (existing slots keep theirs)
    };
    LabelPair side_of(const Change& change) const;
    bool acceptable(const std::vector<Change>& changes, const std::vector<std::uint32_t>& removed);
    bool shape_ok(const Change& change);
    bool clear_of_others(const std::vector<Change>& changes, const std::vector<std::uint32_t>& excluded);
    /// Whether, around every junction edge of a changed triangle, the triangles still turn in the order
    /// their tissues demand (edge_fan.h): the alive ones except `excluded`, and the changes. Always true in
    /// tolerant mode.
    bool fans_in_order(const std::vector<Change>& changes, const std::vector<std::uint32_t>& excluded);
    /// False when edge pq is certainly no junction edge: both ends of one lie on junction curves, so edits
    /// inside patches skip the fans.
    bool may_be_junction_edge(std::uint32_t p, std::uint32_t q) const
    {
        return kinds_[p] != VertexKind::patch && kinds_[q] != VertexKind::patch;
    }
    /// How the triangles around edge pq lie at the current positions: the alive ones except `excluded`
    /// (when given) and the `changes` (when given). With `members`, appends the alive ones to it.
    FanOrder fan_around(std::uint32_t p, std::uint32_t q, const std::vector<Change>* changes,
                        const std::vector<std::uint32_t>* excluded, std::vector<std::uint32_t>* members) const;
    /// Whether triangles a and b (at corners pa, pb: the current positions) meet other than where they share
    /// vertices; exact (triangles_intersect), with the plane test (certainly_apart) in front.
    bool meet(const Triangle& a, const TriangleCorners& pa, const Triangle& b, const TriangleCorners& pb) const;
    /// Intersecting pairs that involve `slots` (alive triangles) at the current positions: among them and
    /// with the other alive triangles. Sets the budget of the next check in tolerant mode.
    std::size_t intersections_involving(const std::vector<std::uint32_t>& slots);
    void set_budget(const std::vector<std::uint32_t>& slots);
    /// The rule a moved triangle `t` breaks at the current positions (0: none), `start` holding the
    /// positions before the batch; `judged` marks the triangles judged in the same round (a pair of two
    /// of them is judged by the smaller index only). With `partners`, collects every triangle t meets or
    /// crowds instead of stopping at the first.
    std::uint8_t judge_moved(std::uint32_t t, const std::vector<Vec3>& start, const std::vector<char>& judged,
                             const BoxIndex& index, std::vector<std::uint32_t>* partners) const;
    /// The rule the pair of moved triangle t (at `now`, formerly `before`, tight box `tight`) and triangle u
    /// breaks at the current positions (0: none).
    std::uint8_t pair_rule(std::uint32_t t, std::uint32_t u, const TriangleCorners& now, const TriangleCorners& before,
                           const Box3& tight, const std::vector<Vec3>& start) const;
    /// Makes batch_index_ fit for a batch whose `changed` triangles have their boxes for the batch in boxes_.
    void refresh_batch_index(const std::vector<std::uint32_t>& changed);
    /// Builds the neighbour grid if an edit needs it and it is not built (after rebuild_grid() or
    /// move_together(), which judges against its own index and leaves the grid to be rebuilt).
    void ensure_grid();
    bool link_condition(std::uint32_t v, std::uint32_t w) const;
    void apply(const std::vector<Change>& changes, const std::vector<std::uint32_t>& removed);
    std::uint32_t add_vertex(const Vec3& p);

    EditLimits limits_;
    AngleLimit min_angle_; ///< limits_.min_angle_deg
    AngleLimit max_tilt_;  ///< limits_.max_normal_change_deg
    TriangleGrid grid_;
    double grid_cell_mm_ = 1; ///< cell size asked of the grid
    bool grid_ready_ = false; ///< grid_ files every alive triangle under its current box
    BoxIndex batch_index_;    ///< move_together()'s index (see refresh_batch_index())
    bool batch_index_valid_ = false;
    std::vector<CompactBox> boxes_;       ///< per triangle slot: its bounding box now (alive slots)
    std::vector<std::uint32_t> nearby_;   ///< scratch for grid queries
    std::size_t intersection_budget_ = 0; ///< intersections the next check may leave (tolerant mode)
    EditCounters counters_;
    // Scratch kept between calls, so that an edit (collapses are tried millions of times) allocates nothing
    // once the buffers have grown. fan_around() and judge_moved() keep theirs thread_local instead: they run
    // in parallel within move_together().
    std::vector<std::uint32_t> collapse_removed_, collapse_excluded_, collapse_common_; ///< try_collapse()
    std::vector<Change> collapse_changes_;                                              ///< try_collapse()
    mutable std::vector<RingEntry> link_ring_v_, link_ring_w_;                          ///< link_condition()
    mutable std::vector<std::uint32_t> link_apexes_;                                    ///< link_condition()
    std::vector<TriangleCorners> clear_shapes_;                                         ///< clear_of_others()
    std::vector<Box3> clear_boxes_;                                                     ///< clear_of_others()
    std::vector<const TriangleCorners*> clear_before_;                                  ///< clear_of_others()
    std::vector<std::pair<std::uint32_t, std::uint32_t>> fan_edges_;                    ///< fans_in_order()
};

/// The tissues on either side of the triangles around vertex `v`, sorted, each once.
std::vector<Label> tissues_around(const ComplexEditor& editor, std::uint32_t v);

} // namespace tissuemesh::surface::detail

// LocalEditor: collapses, splits, flips and moves on an interface complex, each judged only where it
// happens, so that an edit costs a few microseconds whatever the size of the complex. The engine of
// decimate() and remesh().
//
// What is judged, and why that is all that can break (the complex was valid before the edit):
//  - topology: the link condition (Dey, Edelsbrunner, Guha, Nekhayev 1999) for collapses, junction rules
//    (a vertex on a junction curve moves and collapses only along it; curve corners stay), and flips only
//    inside one patch on edges of two triangles;
//  - each new triangle: not degenerate, no angle below the limit (unless no smaller than the smallest
//    angle of the triangle it replaces), no tilt beyond the limit against it, no edge over the length limit;
//  - triangles sharing a vertex with a new one: the star of every vertex of the new triangles (star_check.h:
//    one linear test per fan, exact predicates where unsure);
//  - triangles sharing no vertex with a new one: those whose boxes come within the gap, from a grid, must
//    neither meet it (exact) nor come closer than the gap unless they were as close before;
//  - around every junction edge of a new triangle, the triangles keep the order their tissues demand
//    (edge_fan.h).
// An edit is applied, judged, and undone when refused; it never changes anything outside its star.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "core/interface_complex.h"
#include "surface/detail/edge_fan.h"
#include "surface/detail/edit_types.h"
#include "surface/detail/editable_complex.h"
#include "surface/detail/slabs.h"
#include "surface/detail/triangle_grid.h"

namespace tissuemesh::surface::detail {

/// Limits every edit keeps. Lengths in mm, angles in degrees.
struct LocalLimits {
    double min_angle_deg = 5; ///< new triangles' smallest angle (unless not worse than before)
    double max_tilt_deg = 45; ///< a new triangle's normal against the one of the triangle it replaces
    double min_gap_mm = 0.1;  ///< triangles sharing no vertex keep this distance (unless closer before)
    double max_edge_mm = 0;   ///< collapses and flips may not make a longer edge (0: no bound)
    /// Around every edge of a new triangle, the angle between neighbouring triangles (holding a tissue, or
    /// background that tm-tetra meshes where tissues enclose it) keeps at least this much, unless the edit makes the
    /// smallest such angle near it no smaller (0: no rule). Why: every tet of that tissue at the edge lies inside the
    /// angle, so its dihedral angle there is no larger; a thin tissue tapering out at a junction curve, or a sharp
    /// crease, leaves tm-tetra only slivers (measured on the 1 mm usc19-5 head: remeshing without the rule turned 77
    /// such angles under 10 degrees at junction edges into 197).
    double min_sector_deg = 0;
};

/// The limits a step's options ask of the editor (DecimateOptions and RemeshOptions name them alike).
template <class StepOptions>
LocalLimits limits_of(const StepOptions& options)
{
    return {.min_angle_deg = options.min_angle_deg,
            .max_tilt_deg = options.max_normal_change_deg,
            .min_gap_mm = options.min_gap_mm,
            .min_sector_deg = options.min_sector_deg};
}

/// A small closed piece of one tissue (LocalEditor::small_pieces).
struct SmallPiece {
    Label tissue = 0;
    double volume = 0; ///< enclosed by its triangles, positive with the tissue inside
    double area = 0;
};

class LocalEditor : public EditableComplex {
public:
    /// Takes the complex over; `cell_mm` is the neighbour grid's cell (about twice the longest edge expected).
    /// @pre `complex` passes check_complex()
    LocalEditor(InterfaceComplex complex, const LocalLimits& limits, double cell_mm);

    /// Files every alive triangle again in a grid of `cell_mm` (after triangles grew or shrank a lot).
    void rebuild_grid(double cell_mm);
    const LocalLimits& limits() const { return limits_; }
    void set_limits(const LocalLimits& limits);
    const EditCounters& counters() const { return counters_; }
    /// Confines the edits to a fence (every triangle an edit removes or makes lies inside); nullopt: anywhere.
    void set_fence(const std::optional<EditFence>& fence) { fence_ = fence; }
    /// Whether every one of `triangles` lies inside the fence (true without a fence).
    bool inside_fence(const std::vector<std::uint32_t>& triangles) const;

    /// Collapses edge vw into w (v disappears, w stays where it is). `veto`, when given, is asked after the
    /// cheap checks and before the costly ones; false refuses (counted by the caller).
    bool try_collapse(std::uint32_t v, std::uint32_t w, const std::function<bool()>& veto = {});
    /// Splits edge vw (every triangle on it) at p; returns the new vertex.
    std::optional<std::uint32_t> try_split(std::uint32_t v, std::uint32_t w, const Vec3& p);
    /// Replaces edge vw (two triangles of one patch) by the edge between their third corners.
    bool try_flip(std::uint32_t v, std::uint32_t w);
    /// Moves v to p (the caller keeps curve vertices on their curves and corners in place).
    bool try_move(std::uint32_t v, const Vec3& p);
    /// Contracts `cluster` (connected patch vertices of one patch, `r` among them) into r, which stays
    /// where it is: the triangles around the cluster, which must form a disc whose rim has at least 4 vertices, become
    /// the fan of r over that rim (the rim's triangles keep their slots; those with two or three cluster vertices
    /// die). The same as collapsing the others into r one by one, judged once, as a collapse is. `veto` as for
    /// try_collapse(). Returns whether it was applied.
    bool try_contract(const std::vector<std::uint32_t>& cluster, std::uint32_t r,
                      const std::function<bool()>& veto = {});
    /// While a veto of try_contract() is asked: the triangles the contraction reshapes (each with one cluster vertex,
    /// which becomes r) and those it removes.
    const std::vector<std::uint32_t>& pending_changed() const { return edit_.changed; }
    const std::vector<std::uint32_t>& pending_dying() const { return edit_.dying; }

    /// The complex, compacted (dead vertices and triangles dropped, order otherwise kept).
    InterfaceComplex result() const;

    /// How many triangles the piece of `tissue` at v is counted to have (0 when no triangle at v has that tissue
    /// on a side): at most the triangles with `tissue` on a side reachable from v through shared vertices
    /// (small_pieces() trusts a count above its limit and searches no further).
    std::size_t counted_piece(std::uint32_t v, Label tissue) const;

private:
    struct Saved {
        std::uint32_t triangle;
        Triangle corners;
        char alive;
    };
    using CellRange = std::array<std::uint16_t, 6>;
    using Prior = std::pair<std::uint32_t, std::array<Vec3, 3>>; ///< a changed triangle and its corners before

    bool shape_ok(const Triangle& now, const Triangle& before, bool check_tilt);
    /// The end of a collapse or contraction applied around `kept` (edit_ holds its changed, dying and prior
    /// triangles and the small pieces before): judged by the sector rule, the surroundings and the small pieces, undone
    /// when refused, else its triangles filed again.
    template <class Before>
    bool judge_merge(std::uint32_t kept, Before sectors_before, bool pieces_clear);
    /// edit_.prior: each of edit_.changed with its corners now (before the edit is applied).
    void keep_prior();
    /// Judges the triangles `changed` (alive, at current positions) against their surroundings: stars of
    /// their vertices, triangles from the grid, junction fans. `before` maps each to its prior corners (for
    /// the gap rule; none for new triangles).
    bool surroundings_ok(const std::vector<std::uint32_t>& changed, const std::vector<Prior>& before);
    struct Box {
        Vec3 low, high;
    };
    /// Calls visit(u, its filed box) for every alive triangle filed in the cells of r, whose box may overlap `box`
    /// and passes near(its filed box), and not yet stamped with the current query (stamping it); true at the first
    /// visit that returns true.
    template <typename Near, typename Visit>
    bool any_in_cells(const CellRange& r, const Box& box, const Near& near, const Visit& visit);
    /// Whether vertex v, moved in a straight line from `from` to `to`, passes through a triangle outside its
    /// star (exact). Each step of a smoothing or relaxation may be valid where it ends and still carry a vertex
    /// through the surface: a small closed piece (a tetrahedron of four triangles around a two-voxel pocket)
    /// flattened over a few moves and then pushed through its opposite face ends inside out, intersection-free,
    /// with every tilt small; its tissue then claims the space around it (TetGen's tets disagree on their tissue).
    bool path_crosses(std::uint32_t v, const Vec3& from, const Vec3& to);
    /// The small pieces of tissue around v: for each tissue (not the background) on a side of a triangle at v,
    /// the triangles with that tissue on a side reachable from v through shared vertices, when there are at
    /// most 24 of them (a closed island: a white-matter speck in grey matter, a pocket of one organ between
    /// two others). A collapse or a move may shrink such a piece to a tetrahedron inside out, or flat, or to a
    /// sliver, each new triangle within the tilt limit of the one it replaces and nothing crossing; TetGen
    /// then has only flat tets to fill it with.
    /// Returns whether each tissue it looked at has more than 24 + `margin` such triangles (an edit that
    /// removes at most `margin` of them then leaves no small piece there). Tissues in `known` are skipped.
    bool small_pieces(std::uint32_t v, std::vector<SmallPiece>& out, std::size_t margin = 0,
                      std::span<const Label> known = {});
    /// Whether t and u lie in one patch facing nearly the same way: neighbours along one sheet, which the
    /// gap rule leaves alone (a sheet folding back towards itself faces the other way where it nears).
    bool same_sheet_direction(std::uint32_t t, std::uint32_t u) const;
    /// The gap rule for changed triangle t and triangle `other` sharing no vertex with it.
    bool gap_ok(std::uint32_t t, const std::vector<Prior>& before, std::uint32_t other) const;
    Box box_of(const Triangle& t) const;
    /// Whether closed boxes a and b overlap (inline: asked for every neighbour of every changed triangle).
    static bool overlap(const Box& a, const Box& b)
    {
        return !(a.high[0] < b.low[0] || b.high[0] < a.low[0] || a.high[1] < b.low[1] || b.high[1] < a.low[1] ||
                 a.high[2] < b.low[2] || b.high[2] < a.low[2]);
    }
    std::uint16_t cell_at(double x, int axis) const;
    bool fans_ok(const std::vector<std::uint32_t>& changed);
    /// The smallest angle (degrees) between neighbouring triangles `blades` around edge ab, the background's
    /// included (360 on an edge of one triangle), or clear_sector_deg_ when two triangles meet there at a larger
    /// angle: the rule only compares values under its limit (sectors_ok), so an edge clear of it needs no exact
    /// value.
    double smallest_sector_deg(std::uint32_t a, std::uint32_t b, std::span<const FanBlade> blades) const;
    /// The smallest of smallest_sector_deg() over the edges of `triangles` (alive, current positions); 360
    /// when the sector rule is off.
    double smallest_sector_deg(const std::vector<std::uint32_t>& triangles) const;
    /// The sector rule (LocalLimits::min_sector_deg) for the edit that changed `changed`, whose
    /// neighbourhood's smallest sector was `before()` (smallest_sector_deg() before the edit). `before` is called
    /// only when the sectors after the edit fall under the limit, which few edits do: most never pay for it.
    template <class Before>
    bool sectors_ok(const std::vector<std::uint32_t>& changed, Before before)
    {
        if (!(limits_.min_sector_deg > 0)) return true;
        const double after = smallest_sector_deg(changed);
        if (after >= limits_.min_sector_deg || after >= before() - 1e-9) return true;
        ++counters_.wedge;
        return false;
    }
    void save(std::uint32_t t);
    void undo();
    void remove_from_star(std::uint32_t v, std::uint32_t t);
    CellRange cells_of(const Triangle& t) const;
    void file(std::uint32_t t);
    void unfile(std::uint32_t t);
    std::uint32_t new_triangle(const Triangle& t, const LabelPair& side);

    LocalLimits limits_;
    double cos_min_angle_ = 1, cos_max_tilt_ = 0;
    /// A sector this much (1 degree) over the sector rule's limit is clear of it, and its cosine.
    double clear_sector_deg_ = 1, cos_clear_sector_ = 1;
    // The neighbour grid: each alive triangle is listed in every cell its box overlaps.
    Vec3 grid_origin_{0, 0, 0};
    double cell_mm_ = 1;
    std::array<std::size_t, 3> grid_dims_{1, 1, 1};
    /// A triangle in a cell, with its box when filed in single precision (rounded outwards).
    struct CellEntry {
        std::uint32_t triangle;
        CompactBox box;
    };
    std::vector<std::vector<CellEntry>> cells_;
    std::vector<CellRange> filed_;
    // The edit in progress: what it changed, for undo.
    std::vector<Saved> saved_;
    /// Stars as they were before the edit: (vertex, start, size) into saved_star_items_ (flat, so that saving
    /// a star allocates nothing once the buffers have grown).
    struct SavedStar {
        std::uint32_t vertex, start, size;
    };
    std::vector<SavedStar> saved_stars_;
    std::vector<std::uint32_t> saved_star_items_;
    void save_star(std::uint32_t v);
    /// Forgets what the last edit saved (before a new edit).
    void begin_edit();
    std::size_t triangles_before_edit_ = 0, vertices_before_edit_ = 0;
    std::vector<std::uint32_t> stamp_; ///< per triangle: the query that last met it (candidates once each)
    std::uint32_t query_ = 0;
    std::vector<std::uint32_t> vertex_stamp_; ///< per vertex: the query that last met it (small_pieces)
    std::optional<EditFence> fence_;
    EditCounters counters_;
    // Scratch kept between calls, so that an edit (tried millions of times) allocates nothing once the
    // buffers have grown. The edits (try_*) never call one another and share edit_; the checks they call keep
    // their own. One editor is used by one thread at a time (slabs have an editor each).
    struct EditScratch {
        std::vector<RingEntry> around_v, around_w;
        std::vector<std::uint32_t> common, changed, dying, parents, rim;
        std::vector<std::pair<Label, int>> uses;
        std::vector<Prior> prior;
        std::vector<SmallPiece> pieces_before, pieces_at_w, pieces_after;
    } edit_;
    /// Per triangle, for its `from` and `to` tissue (no_piece for the background): the piece of that tissue it lay
    /// in when the editor started (the triangles with the tissue on a side, joined through shared vertices), which
    /// the triangles split from it inherit; and per piece, how many live triangles carry it. No edit parts a piece
    /// (a collapse keeps the triangles around its dying ones joined at its surviving vertex; splits, flips and
    /// moves keep every vertex's triangles), so a count is at most the size of the piece it names, and a piece
    /// counted above small_pieces()' limit needs no search there.
    static constexpr std::uint32_t no_piece = ~std::uint32_t{0};
    std::vector<std::array<std::uint32_t, 2>> piece_of_;
    std::vector<std::uint32_t> piece_size_;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> saved_piece_sizes_; ///< (piece, count) before the edit
    void count_pieces();
    /// Adds `delta` to the counts of t's pieces, saved for undo.
    void recount(std::uint32_t t, int delta);
    std::vector<FanBlade> blades_;                                    ///< fans_ok()
    std::vector<std::uint32_t> piece_vertices_, piece_triangles_;     ///< small_pieces()
    std::vector<Label> piece_tissues_;                                ///< small_pieces()
    std::vector<Box> boxes_;                                          ///< surroundings_ok()
    mutable std::vector<std::pair<std::uint64_t, int>> sector_edges_; ///< smallest_sector_deg()
    std::vector<std::uint32_t> star_vertices_;                        ///< surroundings_ok()
};

} // namespace tissuemesh::surface::detail

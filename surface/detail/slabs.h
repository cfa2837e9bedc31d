// Slabs: a complex cut into pieces along one axis, for local edits that run on the pieces in parallel and
// are put back together without conflict.
//
// The rule that makes it safe: a piece holds every triangle whose box reaches into its slab [low, high], and
// an edit in it may change only triangles whose boxes lie inside [low + margin, high - margin]. With the
// margin above the gap kept between triangles, two pieces never change triangles that could meet, crowd
// each other or share a vertex, and every triangle an edit is judged against (the neighbours of its changed
// triangles, the stars of their vertices) is in the piece. Each triangle then belongs to the slab holding
// the low end of its box; a changed triangle belongs to the piece that changed it.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/interface_complex.h"

namespace tissuemesh::surface::detail {

/// Where edits may happen: only to triangles whose boxes, before and after the edit, lie within [low, high]
/// along `axis` (ComplexEditor::set_fence()).
struct EditFence {
    int axis = 0;
    double low = 0;
    double high = 0;
    /// Whether the triangle abc lies inside.
    bool holds(const Vec3& a, const Vec3& b, const Vec3& c) const
    {
        return std::min({a[axis], b[axis], c[axis]}) >= low && std::max({a[axis], b[axis], c[axis]}) <= high;
    }
};

/// The part [low, high) of the axis that belongs to one piece (the first and last reach to infinity).
struct Slab {
    int axis = 0;
    double low = 0;
    double high = 0;
    /// Whether a triangle whose box starts at `from` along the axis belongs to this slab.
    bool owns(double from) const { return from >= low && from < high; }
    /// The fence of an edit in this slab: the slab shrunk by more than the gap kept between triangles.
    EditFence fence(double min_gap_mm) const { return {axis, low + min_gap_mm + 0.01, high - min_gap_mm - 0.01}; }
};

/// Cuts the complex into `count` slabs across its longest side, each owning about as many triangles
/// (by the low ends of their boxes). Depends only on the complex and the count.
/// @pre count >= 1
std::vector<Slab> cut_into_slabs(const InterfaceComplex& complex, std::size_t count);

/// Slabs cut halfway between the cuts of `slabs` (one fewer): each old cut lies in the middle of a new
/// slab, half an old slab from its ends. Empty for fewer than three slabs.
std::vector<Slab> slabs_between(const std::vector<Slab>& slabs);

/// The low and high end of triangle t's box along `axis`.
std::pair<double, double> span(const InterfaceComplex& complex, std::uint32_t t, int axis);

/// The triangles whose boxes reach into a slab, as a complex of its own.
struct SlabPiece {
    InterfaceComplex complex;                 ///< the slab's triangles over its own vertex numbering
    std::vector<std::uint32_t> from_vertex;   ///< per piece vertex: its index in the whole complex
    std::vector<std::uint32_t> from_triangle; ///< per piece triangle: its index in the whole complex
};
SlabPiece slab_piece(const InterfaceComplex& complex, const Slab& slab);

/// The one driver of edits in slabs (decimate(), remesh()): calls edit(k, piece) on the piece of every slab
/// k marked in `run` (every slab when `run` is empty), side by side in parallel, each piece on its own, so the
/// result does not depend on the thread count; then, one at a time, finished(n) with the number n of slabs
/// done so far (for progress). The first exception an edit throws is thrown again once all have finished.
void edit_slabs(const InterfaceComplex& complex, const std::vector<Slab>& slabs, const std::vector<char>& run,
                const std::function<void(std::size_t, SlabPiece&)>& edit,
                const std::function<void(std::size_t)>& finished = {});

/// A slab after editing its piece: the edited complex over the piece's vertices (in the piece's order, new
/// ones after), or nullopt when the slab was left as it was.
struct EditedSlab {
    Slab slab;
    std::optional<InterfaceComplex> edited;
    std::vector<std::uint32_t> from_vertex; ///< the piece's (SlabPiece::from_vertex)
};

/// The whole complex again: each triangle from the slab that owns it (slabs of `slabs` cover the axis),
/// vertices that came from the whole numbered as there, new ones after, unused ones dropped (order kept).
InterfaceComplex merge_slabs(const InterfaceComplex& whole, const std::vector<EditedSlab>& slabs);

} // namespace tissuemesh::surface::detail

// Adaptive resolution of snakes: split long edges, collapse short ones, flip towards valence 6, every edit
// through the ComplexEditor's validity checks.
#pragma once

#include <cstddef>
#include <functional>

#include "surface/detail/complex_editor.h"

namespace tissuemesh::surface::detail {

struct ResolutionCounts {
    std::size_t splits = 0;
    std::size_t collapses = 0;
    std::size_t flips = 0;
    std::size_t total() const { return splits + collapses + flips; }
};

/// One pass over the edges of `editor`'s complex: edges longer than 4/3 of their target are split at their
/// midpoint, edges shorter than 4/5 collapsed (unless that would make an edge longer than 4/3 of the
/// target), then edges between two triangles of a patch flipped when that brings the four vertices' valences
/// closer to 6. `target_mm(v)` gives the edge length sought at vertex v; an edge takes the smaller of its
/// two vertices' targets.
ResolutionCounts adapt_resolution(ComplexEditor& editor, const std::function<double(std::uint32_t)>& target_mm);

} // namespace tissuemesh::surface::detail

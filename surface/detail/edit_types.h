// What the complex editors (ComplexEditor, LocalEditor) share with the steps that drive them: the role of
// a vertex in the complex and the reasons edits were refused.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tissuemesh::surface::detail {

/// Where a vertex may go: anywhere on its patch, only along its junction curve, or nowhere.
enum class VertexKind : std::uint8_t { patch, curve, corner };

/// Why edits were refused, for reports.
struct EditCounters {
    std::size_t accepted = 0;
    std::size_t topology = 0;     ///< link condition, junction rules, valence
    std::size_t shape = 0;        ///< degenerate or too small an angle
    std::size_t normal = 0;       ///< tilted too much (a fold)
    std::size_t intersection = 0; ///< would meet another triangle
    std::size_t gap = 0;          ///< would come too close to another triangle
    std::size_t wedge = 0;        ///< would close the wedge with a triangle sharing one vertex, or turn the
                                  ///< triangles around a junction edge out of order (edge_fan.h)
    std::size_t fence = 0;        ///< would change a triangle outside the fence (not a defect)
};

} // namespace tissuemesh::surface::detail

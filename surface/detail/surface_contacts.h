// Where the surfaces of an interface complex cross or touch: the triangle pairs repair() must move apart.
#pragma once

#include <compare>
#include <cstdint>
#include <vector>

#include "surface/detail/complex_editor.h"

namespace tissuemesh::surface::detail {

/// Two triangles (slots, a < b) that cross, or (near-contact) come closer than the gap.
struct Contact {
    std::uint32_t a = 0, b = 0;
    bool crossing = false;
    friend auto operator<=>(const Contact&, const Contact&) = default;
};

/// The crossing pairs among the editor's alive, non-degenerate triangles (exact), and with gap_mm > 0 the
/// pairs of different patches sharing no vertex and joined by no edge whose vertex-to-face distance is below
/// it; sorted.
std::vector<Contact> find_contacts(const ComplexEditor& editor, double gap_mm);

/// Whether two sides are the same patch (the same two tissues, in either order).
bool same_patch(const LabelPair& a, const LabelPair& b);
/// The unit normal of a triangle (zero for a degenerate one).
Vec3 unit_normal(const TriangleCorners& c);
/// Whether the triangle in slot t has collinear corners (exact).
bool degenerate(const ComplexEditor& editor, std::uint32_t t);

} // namespace tissuemesh::surface::detail

// The triangles around one edge, in the order they turn about it. Along a junction curve three or more
// patches share an edge, and the tissue between two neighbouring triangles must be the same seen from
// either of them. A vertex that passes through the plane of a flat pocket (four triangles around a small
// tissue region, seen on the usc19-5 scalp) turns the pocket inside out: no triangle meets another, no
// tissue surface opens, yet around the pocket's edges the order of the triangles now contradicts their
// tissues, and TetGen finds a tetrahedron between interfaces that disagree. The checker and every edit
// test this order.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/interface_complex.h"
#include "core/vec3.h"

namespace tissuemesh::surface::detail {

/// One triangle on the edge from a to b: its third corner, its tissues, and whether its vertex order
/// runs from a to b. A forward triangle's normal, and so the tissue in front of it (`side.to`), faces the
/// way a right-hand turn about b - a moves it; a backward one's faces against that turn.
struct FanBlade {
    Vec3 apex{0, 0, 0};
    LabelPair side{};
    bool forward = true;
};

enum class FanOrder : std::uint8_t {
    in_order,     ///< going round, the tissue ahead of each triangle is the tissue behind the next one
    out_of_order, ///< two neighbouring triangles disagree on the tissue between them: a wedge turned inside out
    overlapping,  ///< two triangles lie in one half-plane about the edge, or one is flat on it
};

/// The blade of triangle `tri` (with tissues `side`, corners in `positions`) on its edge from a to b.
/// @pre tri holds a and b
inline FanBlade blade_on(const Triangle& tri, std::uint32_t a, std::uint32_t b, const std::vector<Vec3>& positions,
                         const LabelPair& side)
{
    const int k = tri[0] == a ? 0 : tri[1] == a ? 1 : 2;
    const bool forward = tri[(k + 1) % 3] == b;
    return {positions[tri[forward ? (k + 2) % 3 : (k + 1) % 3]], side, forward};
}

/// How the triangles `blades` (at least two) lie around the edge from a to b; exact predicates.
FanOrder fan_order(const Vec3& a, const Vec3& b, std::span<const FanBlade> blades);

/// The smallest angle (degrees) between neighbouring triangles `blades` around the edge from a to b; 360
/// when there are fewer than two blades. Every tet at the edge lies inside such an angle, so its dihedral
/// angle at the edge is no larger: a tissue tapering out at a junction curve, or a sharp crease of one
/// interface, bounds the quality of any tet mesh that keeps the complex. The background's angles count too:
/// tm-tetra meshes the background that tissues enclose (measured on the liver: its worst tets were in such
/// cavities, 6 degrees, while no tissue sector was under 15). Floating point (a measure, not a decision the
/// topology depends on).
double smallest_sector_deg(const Vec3& a, const Vec3& b, std::span<const FanBlade> blades);

/// smallest_sector_deg() over every edge of `complex`.
double smallest_sector_deg(const InterfaceComplex& complex);

} // namespace tissuemesh::surface::detail

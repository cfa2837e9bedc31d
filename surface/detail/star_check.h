// Whether the triangles around one vertex meet each other: in linear time for the usual star, a fan of one
// patch (or, on a junction curve, one fan per patch) whose projection along its mean normal winds once.
//
// Why it is enough: two triangles sharing a vertex can only meet where that vertex's star folds, and a fan
// whose triangles all face one direction n and whose angles about the vertex, seen along n, add up to one
// turn at most, projects one-to-one onto the plane across n, so no two of its triangles meet. Where the
// float test is not certain, or the star is not a set of fans, every pair is tested exactly.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/interface_complex.h"
#include "surface/detail/rows.h"

namespace tissuemesh::surface::detail {

/// The triangles around every vertex, as fans ("sheets"): triangles of one star that share an edge of
/// multiplicity two (not a junction edge) are in one sheet, in the order they turn about the vertex.
struct StarSheets {
    Rows stars;  ///< per vertex: its triangles, sheet after sheet, each sheet in turning order
    Rows sheets; ///< per vertex: where each sheet starts in its row of `stars` (offsets within the row)
    std::vector<std::uint8_t> closed_bits; ///< per vertex: bit s set when sheet s closes on itself (first 8)
    std::vector<char> irregular;           ///< per vertex: its star is not a set of fans (tested pairwise)
};

/// Orders the triangles `star` (all around v) into fans: `order` the triangles sheet after sheet, `starts`
/// where each sheet begins in `order`, bit s of `closed_bits` set when sheet s closes on itself. False when
/// the star is not a set of fans (or has over 64 triangles or 32 sheets).
bool order_sheets(std::uint32_t v, std::span<const std::uint32_t> star, const std::vector<Triangle>& triangles,
                  std::vector<std::uint32_t>& order, std::vector<std::uint32_t>& starts, std::uint32_t& closed_bits);

/// Builds the sheets of every vertex from the triangles around it (`stars`, one row per vertex: star_rows()),
/// side by side (OpenMP); the result does not depend on the thread count.
StarSheets build_star_sheets(const std::vector<Triangle>& triangles, const Rows& stars);

/// Whether triangles a and b meet other than at the vertices and edge they share by index: boxes, then the
/// plane test (certainly_apart), then the exact test (triangles_intersect).
bool triangles_meet(const std::vector<Vec3>& positions, const Triangle& a, const Triangle& b);

/// Whether no two of the triangles `star` (all the triangles around v) meet other than where they share
/// vertices and edges: the sheets are ordered on the fly (for stars that change as a complex is edited).
/// With `changed` (the triangles an edit changed; empty: all), only pairs with a changed triangle and fans
/// holding one are judged: the others were judged before.
bool star_is_clean(std::uint32_t v, std::span<const std::uint32_t> star, const std::vector<Vec3>& positions,
                   const std::vector<Triangle>& triangles, std::span<const std::uint32_t> changed = {});

/// Appends to `offenders` the triangles around `v` that meet another triangle around `v` (other than at
/// the vertices and edges they share), exactly. `positions` hold the current places.
void star_offenders(std::uint32_t v, const StarSheets& sheets, const std::vector<Vec3>& positions,
                    const std::vector<Triangle>& triangles, std::vector<std::uint32_t>& offenders);

} // namespace tissuemesh::surface::detail

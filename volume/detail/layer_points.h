// Nodes inside the tissue layers, given to TetGen with the interface complex.
//
// TetGen, content with radius-edge 2, fills a layer a few edges thick with tets whose four nodes lie on the
// layer's two sides: on the 1 mm sphere head 23 591 of the 35 214 tets under 20 degrees were such tets (docs/volume.md,
// twenty-first session), and the improver spends most of its time on them. A node placed about an edge off each
// interface vertex, into the layer, gives those tets a node to share instead.
//
// Floating point: where the points go is a choice of sizing, not a decision the topology depends on (TetGen
// inserts them with its exact predicates; a point must only lie off every triangle, which the clearance ensures).
#pragma once

#include <vector>

#include "core/interface_complex.h"
#include "core/vec3.h"

namespace tissuemesh::volume::detail {

struct LayerPointsOptions {
    double offset_per_edge = 1.0;     ///< how far off an interface vertex, in its mean edge lengths (at most half the
                                      ///< layer's thickness along the vertex normal)
    double min_offset_per_edge = 0.4; ///< no point where that would be nearer its vertex (in mean edges)
    double clearance = 0.8;           ///< every triangle at least this fraction of the offset away from the point
    double spacing_per_edge = 1.2;    ///< points at least this many mean edges of their vertex apart
};

/// Points off the interface vertices of `complex`, one per side of a vertex whose triangles all separate the same
/// two tissues, into each side but the background's: along the vertex normal, the offset's length or half the
/// layer's thickness there, whichever is less; kept when no triangle is nearer than the clearance allows and no
/// point kept before is nearer than the spacing. In vertex order, so the same complex gives the same points.
/// @return #P points, mm, none on a triangle
std::vector<Vec3> layer_points(const InterfaceComplex& complex, const LayerPointsOptions& options = {});

} // namespace tissuemesh::volume::detail

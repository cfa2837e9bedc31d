// Small measures of interface complexes shared by the surface steps.
#pragma once

#include "core/interface_complex.h"
#include "surface/detail/triangle_distance.h"

namespace tissuemesh::surface::detail {

/// Mean length of the triangles' first edges (a cheap estimate of the typical edge), mm; 1 when empty.
double mean_edge_length(const InterfaceComplex& complex);

/// Smallest interior angle of a triangle, degrees (0 for a degenerate one).
double smallest_angle_deg(const TriangleCorners& corners);

} // namespace tissuemesh::surface::detail

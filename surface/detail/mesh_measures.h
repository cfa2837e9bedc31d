// Small measures of interface complexes shared by the surface steps.
#pragma once

#include "core/interface_complex.h"

namespace tissuemesh::surface::detail {

/// Mean length of the triangles' first edges (a cheap estimate of the typical edge), mm; 1 when empty.
double mean_edge_length(const InterfaceComplex& complex);

} // namespace tissuemesh::surface::detail

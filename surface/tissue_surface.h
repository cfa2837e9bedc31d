// The closed surface of one tissue, cut out of an interface complex.
#pragma once

#include "core/interface_complex.h"

namespace tissuemesh::surface {

/// The boundary of `tissue`'s region: every triangle of `complex` with `tissue` on one side, oriented
/// outward (each result triangle has side {tissue, other}, normal pointing out of the tissue), with
/// only the vertices it uses (in order of first use). Names and background are carried over.
/// @pre  `complex` comes from extract_interfaces() (or passes check_complex()): then the result is a
///       closed, consistently oriented surface
/// @throws InputError when no triangle borders `tissue`
InterfaceComplex tissue_surface(const InterfaceComplex& complex, Label tissue);

} // namespace tissuemesh::surface

// The 4-shell sphere head of tm-phantom spheres4 as the accuracy benchmarks measure against it: brain, CSF,
// skull, scalp to radii 78/80/86/92 mm, 0.33/1.79/0.01/0.43 S/m, centred at the origin.
#pragma once

#include "fem/conductivities.h"
#include "fem/sphere_series.h"

namespace tissuemesh::bench {

/// The head as the analytic series (fem/sphere_series.h) sees it.
inline const fem::LayeredSphere spheres4_series{{78, 80, 86, 92}, {0.33, 1.79, 0.01, 0.43}};

/// The same conductivities by tissue name, for a mesh of the phantom.
inline const fem::ConductivityTable spheres4_conductivities{{"brain", fem::isotropic(0.33)},
                                                            {"csf", fem::isotropic(1.79)},
                                                            {"skull", fem::isotropic(0.01)},
                                                            {"scalp", fem::isotropic(0.43)}};

} // namespace tissuemesh::bench

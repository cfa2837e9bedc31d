// Boundary fidelity against a phantom's exact geometry: how far the vertices of an interface complex lie
// from the exact interfaces they stand for, in voxels.
#pragma once

#include "core/interface_complex.h"
#include "image/phantom.h"

namespace tissuemesh::testing {

struct DistanceFigures {
    double max_voxels = 0;
    double mean_voxels = 0;
};

/// Distance to the exact interface between the two tissues of `pair`; where the voxelisation makes two
/// tissues touch that do not in the phantom (a thin shell broken by sampling), the nearest exact
/// interface of either tissue.
double distance_to_nearest_interface(const image::Phantom& phantom, const Vec3& point, LabelPair pair);

/// Distances of every vertex used by a triangle to the exact interface of (one of) its triangles'
/// tissue pairs, in voxels of the phantom's x spacing.
DistanceFigures phantom_distances(const image::Phantom& phantom, const InterfaceComplex& complex);

} // namespace tissuemesh::testing

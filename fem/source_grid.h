// Source positions for lead fields: a regular grid in chosen tissues, kept away from the other tissues.
#pragma once

#include <vector>

#include "core/tet_mesh.h"

namespace tissuemesh::fem {

/// Settings of source_grid(). Lengths in mm.
struct SourceGridOptions {
    double spacing_mm = 5;      ///< grid step; the points are integer multiples of it along x, y and z (world mm)
    std::vector<Label> tissues; ///< the points lie in tets of these tissues (at least one)
    /// Each point is at least this far from every face where the tissues meet another tissue or the outside
    /// (sources right at a conductivity jump are where every dipole model is least accurate).
    double min_distance_mm = 0;
    std::size_t max_points = 2'000'000; ///< more candidate grid points than this are refused
};

/// The grid points that lie in the chosen tissues at the chosen distance from their boundary, in z, y, x order.
/// @throws InputError when the spacing or distance is not a positive (non-negative) finite length, no tissue is
///         chosen, a chosen tissue is not in the mesh, or the tissues' box holds more than max_points grid points
std::vector<Vec3> source_grid(const TetMesh& mesh, const SourceGridOptions& options);

} // namespace tissuemesh::fem

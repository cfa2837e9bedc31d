// EEG electrodes on the outer surface of a tet mesh: each projected onto the boundary triangle nearest it and
// interpolated there (not snapped to the nearest node).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/tet_mesh.h"
#include "fem/outer_boundary.h"

namespace tissuemesh::fem {

/// A point on the outer surface: the potential there is sum_k weights[k] * phi[nodes[k]] (P1 on the
/// triangle it falls on).
struct SurfacePoint {
    std::array<std::uint32_t, 3> nodes{}; ///< the boundary triangle's nodes
    std::array<double, 3> weights{};      ///< barycentric coordinates of the projection, >= 0, sum 1
    Vec3 position_mm{};                   ///< the projection
    double distance_mm = 0;               ///< from the given point to its projection
};

/// The nearest point of the outer boundary `boundary` of `mesh` to each of `points_mm` (ties to the
/// boundary face that comes first). `names[k]` names point k in messages ("Fp1 (eeg.csv line 3)"); a
/// missing or empty name reads "electrode k+1".
/// @throws InputError when a point lies farther than `max_distance_mm` from the surface (names the point, its
///         position and distance, and the fix), or the boundary has no face
std::vector<SurfacePoint> project_onto_surface(const TetMesh& mesh, const OuterBoundary& boundary,
                                               const std::vector<Vec3>& points_mm,
                                               const std::vector<std::string>& names, double max_distance_mm);

} // namespace tissuemesh::fem

// One tetrahedron's local geometry: its face numbering, and the shape measures every report, chart and
// quality check quotes.
#pragma once

#include <cstddef>
#include <utility>

#include "core/tet_mesh.h"

namespace tissuemesh {

/// The faces of a tet by local corners: face k is the one opposite corner k, ordered so that its right-hand
/// normal points out of a positively oriented tet. The one face numbering of the project (the FE face
/// loops, the mesh checks and the improver read it).
inline constexpr int tet_faces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

/// Smallest and largest dihedral angle (degrees) and radius-edge ratio (circumradius over shortest edge;
/// infinite for a flat tet) of a tet. A regular tet has 70.5 degrees everywhere and a ratio of 0.61.
struct TetShape {
    double min_dihedral_deg, max_dihedral_deg, radius_edge_ratio;
};

/// Smallest and largest dihedral angle (degrees) of tet `t` of `mesh`: the same values as tet_shape()'s, for
/// a sixth of its arc cosines (the angles grow with the cosines of the face normals, so only the extremes are
/// turned into angles).
/// @pre t < mesh.tets.size() and its vertex indices are in range
std::pair<double, double> dihedral_range_deg(const TetMesh& mesh, std::size_t t);

/// The shape of tet `t` of `mesh`.
/// @pre t < mesh.tets.size() and its vertex indices are in range
TetShape tet_shape(const TetMesh& mesh, std::size_t t);

} // namespace tissuemesh

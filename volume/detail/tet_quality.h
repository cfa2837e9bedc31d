// The shape measure of the mesh improver: the sines of a tet's six dihedral angles, and their gradients
// with respect to one corner (for smoothing by non-smooth optimisation).
#pragma once

#include <array>

#include "core/vec3.h"

namespace tissuemesh::volume::detail {

using TetCorners = std::array<Vec3, 4>;

/// Edges of a tet by local corners; edge e joins edge_corners[e][0] and [1], and its two faces are the
/// faces opposite edge_corners[e][2] and [3] (the other two corners).
inline constexpr int edge_corners[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                                           {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};

/// sin(theta_e) = 6V * l_e / (4 A_f A_g) for each edge e (faces f, g on it): the sine of the dihedral angle
/// at e, with the sign of the volume (negative for an inverted tet). A regular tet has sqrt(8)/3 everywhere.
/// The smallest of the six is small for every kind of bad tet (slivers, caps, needles, wedges): a
/// dihedral angle near 0 or near 180 degrees. Computed in doubles: for ranking, not for validity.
std::array<double, 6> dihedral_sines(const TetCorners& p);

/// The smallest of dihedral_sines(p): the tet's quality, larger is better.
double min_sine(const TetCorners& p);

/// Gradients of the six sines with respect to corner k, from d log sin = d log 6V + d log l_e - d log A_f -
/// d log A_g. Zero where a face has no area.
std::array<Vec3, 6> dihedral_sine_gradients(const TetCorners& p, int k, const std::array<double, 6>& sines);

/// Whether the tet is positively oriented, decided exactly (Shewchuk's orient3d): det[b-a, c-a, d-a] > 0.
bool positive(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// The quality as a smallest dihedral angle in degrees (asin of the smallest sine, or its supplement when
/// that angle is obtuse), for reports. Flat or inverted tets give 0.
double min_dihedral_deg(const TetCorners& p);

/// A quality threshold for an angle in degrees: sin(angle), the min_sine() of a tet whose angles all lie in
/// [angle, 180 - angle].
double sine_of_deg(double angle_deg);

} // namespace tissuemesh::volume::detail

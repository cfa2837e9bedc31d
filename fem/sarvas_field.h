// The magnetic field of a current dipole in a spherically symmetric conductor (Sarvas 1987, Phys Med Biol
// 32:11): it depends neither on the conductivities nor on the radii of the shells, only on the centre. The
// reference every MEG accuracy figure of ours is measured against (tests/leadfield, bench/measure).
#pragma once

#include "core/vec3.h"

namespace tissuemesh::fem {

/// Vacuum permeability (T*m/A), 4 pi 1e-7 as MNE-Python and FieldTrip take it.
inline constexpr double mu0_t_m_per_a = 4e-7 * 3.14159265358979323846;

/// B (T) at `sensor_mm` (outside the conductor) of the dipole `moment_am` (A*m) at `position_mm` (inside it),
/// for a conductor whose shells are centred at `centre_mm`:
///     B = mu0 / (4 pi F^2) (F q x r0 - (q x r0 . r) grad F),  a = r - r0,
///     F = |a| (|r| |a| + |r|^2 - r0 . r),
///     grad F = (|a|^2 / |r| + a . r / |a| + 2 |a| + 2 |r|) r - (|a| + 2 |r| + a . r / |a|) r0,
/// with r and r0 the sensor and dipole positions from the centre, in metres.
Vec3 sarvas_field(const Vec3& sensor_mm, const Vec3& position_mm, const Vec3& moment_am,
                  const Vec3& centre_mm = {0, 0, 0});

} // namespace tissuemesh::fem

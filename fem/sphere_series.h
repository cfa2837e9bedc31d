// Analytic potential on the surface of concentric conducting spheres from a current dipole in the
// innermost sphere (insulated outer surface), by the Legendre series: in each layer the degree-n term is
// (A r^n + B r^-(n+1)) times the angular function; the innermost layer adds the dipole's own expansion;
// potential and normal current are continuous at every interface and the radial current vanishes
// outside. Solved per degree as a small linear system (written from that definition). The reference every
// EEG accuracy figure of ours is measured against (tests/fem, bench/measure/tm_bench_eeg.cpp).
#pragma once

#include <vector>

#include "core/vec3.h"

namespace tissuemesh::fem {

struct LayeredSphere {
    std::vector<double> radii_mm;      ///< increasing; the last is the outer surface
    std::vector<double> sigma_s_per_m; ///< conductivity inside radii_mm[0], then of each shell
};

/// Potential (V) at `surface_point_mm` (on the outer sphere, centre at the origin) of the dipole with
/// moment `moment_am` (A*m) at `position_mm` (inside radii_mm[0]).
double sphere_surface_potential(const LayeredSphere& sphere, const Vec3& position_mm, const Vec3& moment_am,
                                const Vec3& surface_point_mm, int terms = 150);

/// The same at many points (one per surface point, in order): the series' radial factors, which do not
/// depend on the point, are solved for once.
std::vector<double> sphere_surface_potentials(const LayeredSphere& sphere, const Vec3& position_mm,
                                              const Vec3& moment_am, const std::vector<Vec3>& surface_points_mm,
                                              int terms = 150);

/// How numeric surface potentials agree with analytic ones, both average-referenced: the relative
/// difference measure RDM (0..2: the distance between the two unit-norm patterns) and the magnitude
/// ratio MAG (numeric norm / analytic norm).
struct Agreement {
    double rdm = 0, mag = 0;
};
Agreement compare_potentials(std::vector<double> numeric, std::vector<double> analytic);

} // namespace tissuemesh::fem

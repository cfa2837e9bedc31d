// The magnetic field of a stationary current at MEG sensors: the primary current of the dipoles by Biot-Savart,
// and the volume currents -sigma grad(phi) of the FE solution by Biot-Savart over the tets (Geselowitz'
// secondary field in its volume form, which also holds in anisotropic tissues).
//
// Units: positions mm, moments A*m, conductivities S/m, potentials V, fields T.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/tet_mesh.h"
#include "fem/conductivities.h"
#include "fem/solve_potential.h"

namespace tissuemesh::fem {

/// A magnetometer (one coil: B . normal at position_mm) or a gradiometer (a second coil with the same normal,
/// subtracted: B(position) . normal - B(second_coil) . normal), point coils.
struct MegSensor {
    Vec3 position_mm{};
    Vec3 normal{0, 0, 1};               ///< unit vector
    std::optional<Vec3> second_coil_mm; ///< a gradiometer's second coil
    std::string name;                   ///< for messages; empty: "MEG sensor <n>"
};

/// What `sensor` measures of the primary current of `dipole` (T): mu0/(4 pi) p x (x - x0) / |x - x0|^3 . n.
double primary_field(const MegSensor& sensor, const Dipole& dipole);

/// Settings of the volume-current integral.
struct VolumeCurrentOptions {
    /// Each tet's integral of (x - y)/|x - y|^3 uses the 4-point degree-2 rule, on the 8 midpoint children of
    /// a tet while its longest edge exceeds this fraction of its centre's distance to the coil.
    double split_ratio = 0.5;
    int max_splits = 4; ///< at most this many levels of children (8^4 for the tets nearest the coil)
};

/// The volume-current kernel of `sensor`: for P1 potentials phi (V) on `mesh`, the field of the volume
/// currents is sum_i kernel[i] * phi[i] (T), i.e. -mu0/(4 pi) sum over tets of sigma grad(phi) . (g x n) with g
/// the tet's integral of (x - y)/|x - y|^3. The kernel sums to zero (constants carry no current). #V entries.
/// Parallel over tets, summed in tet order (same bytes for any thread count).
/// @pre every tet is positively oriented (assemble_stiffness() passes); the coils are outside the mesh
std::vector<double> volume_current_kernel(const TetMesh& mesh, const Conductivities& conductivities,
                                          const MegSensor& sensor, const VolumeCurrentOptions& options = {});

/// What `sensor` measures of a solved problem (T): the primary field of `dipoles` plus the volume currents of
/// `potential_v` (#V, V). For tests and single solves; lead fields use the kernel through a transfer matrix.
double magnetic_field(const TetMesh& mesh, const Conductivities& conductivities, const std::vector<double>& potential_v,
                      const std::vector<Dipole>& dipoles, const MegSensor& sensor,
                      const VolumeCurrentOptions& options = {});

} // namespace tissuemesh::fem

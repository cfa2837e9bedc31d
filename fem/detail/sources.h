// Right-hand sides of electrodes and dipoles, and the point location they need.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "fem/outer_boundary.h"
#include "fem/solve_potential.h"

namespace tissuemesh::fem::detail {

/// The boundary nodes of an electrode and each node's share of the patch area (a third of every patch
/// face it belongs to; patch faces have all three nodes inside the radius).
struct ElectrodePatch {
    std::vector<std::uint32_t> nodes;
    std::vector<double> node_area_mm2; ///< parallel to nodes
    double area_mm2 = 0;
};

/// How messages name electrode `index` (0-based): its name, or "electrode N" (1-based) when it has none.
std::string electrode_label(const Electrode& electrode, std::size_t index);

/// @throws InputError when the patch holds no boundary face (names the electrode, its centre and radius)
ElectrodePatch electrode_patch(const TetMesh& mesh, const OuterBoundary& boundary, const Electrode& electrode,
                               std::size_t index);

/// Index of the tet containing `point_mm` (the most interior one when the point is on a shared face).
/// @throws InputError when no tet contains the point
std::size_t locate_tet(const TetMesh& mesh, const Vec3& point_mm, const std::string& what);

/// Adds the partial-integration load b_i += p . grad(phi_i)(x0) of `dipole` (A) to `rhs`.
void add_dipole_load(const TetMesh& mesh, const Dipole& dipole, std::size_t index, Eigen::VectorXd& rhs);

} // namespace tissuemesh::fem::detail

// The multipolar Venant source model: a current dipole replaced by monopoles (point currents) on the nodes
// around it, whose moments match the dipole's.
//
// A distribution of point currents q_k at x_k has the moments sum q_k (x_k - x0)^alpha about the dipole
// position x0; the dipole p delta(x - x0) (its source term -div(p delta)) has moment 0 of order 0, p of
// order 1 and 0 of every higher order. In a homogeneous region the potential of the monopoles far from
// them is the multipole series of these moments; of the second moments S = sum q_k d_k d_k^T only the
// traceless part S - tr(S) I / 3 enters it (the trace multiplies the Laplacian of 1/r, which is zero), so
// the multipolar model asks for (Vorwerk, Hanrath, Wolters, Grasedyck 2019, NeuroImage, on the multipole
// approach for EEG forward modelling with finite elements; after the Venant model of Buchner et al. 1997,
// Electroencephalography and Clinical Neurophysiology, which matches the full moments per axis):
//     order 0:  sum q_k = 0                  order 1:  sum q_k d_k = p
//     order 2:  traceless part of sum q_k d_k d_k^T as small as possible,
// with d_k = (x_k - x0) / a scaled by a reference length a, and the regulariser lambda sum (|d_k|^r q_k)^2
// that keeps the currents small and near the dipole. Orders 0 and 1 are imposed exactly here (Lagrange
// multipliers) rather than in the least-squares sum as in the papers: the loads then sum to zero to
// round-off, as the insulated problem needs, and carry the dipole moment exactly, as partial integration's
// do; the order-2 misfit and the regulariser are minimised over the currents that satisfy them.
// The nodes: the corner of the dipole's tet nearest the dipole and every node of the tets around that
// corner that have the source tet's conductivity tensor (the monopoles stay in the source tissue, up to
// its boundary): 11 to 24 nodes on our meshes, more than the 9 conditions, so the traceless second
// moment vanishes up to the regulariser's trade-off (3e-5 of |p| times the edge length in the unit test,
// against 0.2 to 3 for partial integration) and the regulariser picks the smallest currents, weighted by
// distance, among those that do.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "fem/conductivities.h"
#include "fem/solve_potential.h"

namespace tissuemesh::fem::detail {

/// Point currents standing in for one dipole.
struct Monopoles {
    std::vector<std::uint32_t> nodes; ///< mesh nodes, increasing
    std::vector<double> currents_a;   ///< parallel to nodes, A; they sum to zero
};

/// The monopoles of unit moments (1 A*m) along x, y and z at one position: any moment's currents are their
/// combination with the moment's components.
struct VenantBasis {
    std::vector<std::uint32_t> nodes;                   ///< mesh nodes, increasing
    std::array<std::vector<double>, 3> unit_currents_a; ///< per axis, parallel to nodes, A per A*m
};

/// The corner of tet `source` nearest `position_mm` (the first of equally near ones).
std::uint32_t nearest_corner(const TetMesh& mesh, std::size_t source, const Vec3& position_mm);

/// The Venant basis at `position_mm` in tet `source`, with `around` the tets around
/// nearest_corner(source): the monopoles sit on their nodes in the source's conductivity. `index` names the
/// dipole in messages (0-based).
/// @throws InputError when the options are out of range
/// @throws AlgorithmError when the moment equations have no solution on those nodes (a flat tet)
VenantBasis venant_basis(const TetMesh& mesh, const Conductivities& conductivities, const Vec3& position_mm,
                         std::size_t index, std::size_t source, const std::vector<std::uint32_t>& around,
                         const VenantOptions& options);

/// The monopoles of `dipole` (the `index`-th, for messages).
/// @throws InputError when the dipole lies outside the mesh
/// @throws AlgorithmError when the moment equations have no solution on the chosen nodes (they always do
///         unless the mesh has a degenerate tet)
Monopoles venant_monopoles(const TetMesh& mesh, const Conductivities& conductivities, const Dipole& dipole,
                           std::size_t index, const VenantOptions& options);

/// Adds the monopoles' currents (A) of `dipole` to `rhs`.
void add_venant_load(const TetMesh& mesh, const Conductivities& conductivities, const Dipole& dipole, std::size_t index,
                     const VenantOptions& options, Eigen::VectorXd& rhs);

} // namespace tissuemesh::fem::detail

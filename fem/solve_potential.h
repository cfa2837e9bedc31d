// Stationary current / electrostatics: div(sigma grad phi) = div(j_primary) on a labelled tet mesh with
// an insulated outer boundary, electrodes, current dipoles and fixed potentials.
//
// Units: positions mm, conductivities S/m, currents A, dipole moments A*m, potentials V (the mesh's mm
// are converted to m in assembly, see fem/assemble.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/progress.h"
#include "core/tet_mesh.h"
#include "fem/conductivities.h"
#include "fem/solve.h"

namespace tissuemesh::fem {

/// A scalp electrode: the outer-boundary nodes within `radius_mm` (straight-line distance) of `centre_mm`.
struct Electrode {
    enum class Mode { current, potential };
    Vec3 centre_mm{};          ///< patch centre, world mm (need not lie on the surface)
    double radius_mm = 5;      ///< patch radius, mm
    Mode mode = Mode::current; ///< inject a total current, or hold the patch at a potential
    double current_a = 0;      ///< total current into the body, A (Mode::current), spread over the patch
                               ///< area: uniform normal current density
    double potential_v = 0;    ///< patch potential, V (Mode::potential)
    std::string name;          ///< how messages call it ("C3 (montage.csv line 4)"); empty: "electrode <n>"
};

/// A current dipole: primary current p * delta(x - position). See DipoleModel for its treatment.
struct Dipole {
    Vec3 position_mm{}; ///< world mm, inside the mesh
    Vec3 moment_am{};   ///< A*m
};

/// How a dipole's singularity enters the FE system.
enum class DipoleModel {
    /// b_i = p . grad(phi_i)(position) in the tet that contains the position: needs no homogeneous region,
    /// has no free parameter, keeps sum(b) = 0 exactly and costs one point location. The loads carry the
    /// dipole moment exactly but also a spurious quadrupole of the size of that one tet, set by its shape
    /// and the moment's direction in it: the error varies from tet to tet by a factor of 5 or more and grows as the
    /// dipole nears a conductivity jump (measured in docs/fem.md).
    partial_integration,
    /// phi = phi_inf + phi_corr: the dipole's exact potential in an unbounded medium of the source tissue's
    /// conductivity plus a smooth P1 correction whose loads are integrals over the tissues of other
    /// conductivity and the outer boundary (fem/detail/subtraction.h). Far more accurate near interfaces
    /// (see docs/fem.md); needs an isotropic tissue at the source and a source off the nodes, and costs a
    /// quadrature pass over the tets of other conductivity per dipole. Nodal potentials (and E, J from
    /// them) then hold the singular part too.
    subtraction,
    /// St. Venant's principle in its multipolar form (Buchner et al. 1997, Vorwerk et al. 2019;
    /// fem/detail/venant.h): point currents on the node nearest the dipole and its neighbours in the source
    /// tissue, chosen so that they carry the dipole's moment, no net current and no traceless second moment
    /// (the part of the second moments the potential at a distance sees), regularised to keep them small.
    /// Works in any tissue and on nodes, costs what partial integration costs, and is as accurate as
    /// subtraction or better near the interfaces (see docs/fem.md): it spreads the source over a node
    /// star, so it does not carry the quadrupole of the one tet that holds the dipole.
    venant,
};

/// Settings of DipoleModel::venant (unitless unless named); the defaults are the literature's (Buchner et
/// al. 1997; Vorwerk et al. 2019). The currents hardly depend on them: with 11 to 24 nodes the moment
/// conditions leave room, and the regulariser only picks the smallest currents among those that meet them.
struct VenantOptions {
    double reference_length_mm = 20; ///< a: node offsets enter the moment equations as (x_k - x0) / a
    double regularisation = 1e-6;    ///< lambda: weight of the current-size penalty against the order-2 misfit
    int weighting_exponent = 1;      ///< r: a node's current is penalised with weight (|x_k - x0| / a)^r
};

/// Dirichlet nodes: node indices with their potentials (V).
struct FixedPotentials {
    std::vector<std::uint32_t> nodes;
    std::vector<double> values_v;
};

/// How the potential is made unique when no node has a fixed potential (pure Neumann problem).
enum class Reference {
    zero_mean, ///< the nodal potentials average to zero
    node,      ///< the potential at `reference_node` is zero
};

struct PotentialProblem {
    std::vector<Electrode> electrodes;
    std::vector<Dipole> dipoles;
    DipoleModel dipole_model = DipoleModel::partial_integration; ///< for every dipole
    VenantOptions venant;                                        ///< used only with DipoleModel::venant
    FixedPotentials fixed;                                       ///< inner Dirichlet conditions (electrodes add theirs)
    Reference reference = Reference::zero_mean;                  ///< used only when nothing is fixed
    std::uint32_t reference_node = 0;                            ///< node index for Reference::node
};

struct PotentialReport {
    SolverReport solver;
    std::size_t unknowns = 0;                 ///< free nodes solved for
    std::size_t fixed_nodes = 0;              ///< nodes with a Dirichlet value (electrodes included)
    std::vector<std::size_t> electrode_nodes; ///< boundary nodes per electrode
    std::vector<double> electrode_area_mm2;   ///< patch area per electrode (faces with 3 nodes inside)
    double loads_seconds = 0;                 ///< outer boundary, electrode patches, dipole location, fixed nodes
    double assembly_seconds = 0;              ///< renumbering for locality and the stiffness matrix
    double reduction_seconds = 0;             ///< the system on the free nodes (the solver's times are in `solver`)
};

/// Nodal potentials (V, #V) of the problem.
/// @throws InputError when a dipole lies outside the mesh (or, for subtraction, in an anisotropic tissue or
///         on a node), the Venant options are out of range, an electrode covers no boundary face, node
///         indices are out of range, a node gets two different fixed potentials, or the injected currents
///         do not sum to zero while nothing is fixed (the insulated body would have no solution)
/// @throws AlgorithmError when CG does not converge (see solve_spd), or the Venant moment conditions have no
///         unique solution (only next to a flat tet)
std::vector<double> solve_potential(const TetMesh& mesh, const Conductivities& conductivities,
                                    const PotentialProblem& problem, const SolverOptions& options = {},
                                    const Progress& progress = {}, PotentialReport* report = nullptr);

} // namespace tissuemesh::fem

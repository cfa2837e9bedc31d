// The tDCS lead field (SimNIBS's layout): the potential everywhere for 1 A driven from each electrode into a
// common reference electrode, one solve each with the AMG hierarchy set up once. Fields are linear in the
// currents, so the field of any montage over these electrodes is a sum of rows, without a new solve.
//
// Units: positions mm, conductivities S/m, potentials V per A.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "core/progress.h"
#include "core/tet_mesh.h"
#include "fem/conductivities.h"
#include "fem/solve.h"
#include "fem/solve_potential.h"

namespace tissuemesh::fem {

/// Row k: the nodal potentials (V per A, zero mean over the nodes) for +1 A into electrode
/// `electrodes[k]` and -1 A out of the reference, each spread over its patch as solve_potential() spreads a
/// current electrode's (uniform normal current density).
struct TdcsLeadField {
    std::size_t reference = 0;           ///< the reference electrode (index into the input)
    std::vector<std::size_t> electrodes; ///< the others, in input order: one row each
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> potentials_v_per_a; ///< #rows by #V
};

struct TdcsLeadFieldReport {
    ColumnsReport solver;
    std::vector<std::size_t> electrode_nodes; ///< boundary nodes per electrode patch (input order)
    std::vector<double> electrode_area_mm2;   ///< patch area per electrode
    double assembly_seconds = 0;              ///< renumbering, stiffness matrix, reduction, patches
};

/// The lead field of the electrode patches `electrodes` (centre, radius, name; mode and current are not used)
/// against `electrodes[reference]`.
/// @throws InputError when there are fewer than 2 electrodes, the reference is out of range, or a patch covers
///         no boundary face (names the electrode)
/// @throws AlgorithmError when a solve does not converge
TdcsLeadField compute_tdcs_lead_field(const TetMesh& mesh, const Conductivities& conductivities,
                                      const std::vector<Electrode>& electrodes, std::size_t reference,
                                      const SolverOptions& options = {}, const Progress& progress = {},
                                      TdcsLeadFieldReport* report = nullptr);

/// The nodal potentials (V) of a montage: currents_a[k] (A, into the body) through electrode k of the lead
/// field's input order, the reference included; they must sum to zero (what goes in comes out).
/// @throws InputError when the sizes differ or the currents do not sum to zero (1e-9 of their magnitudes)
std::vector<double> montage_potential(const TdcsLeadField& lead_field, const std::vector<double>& currents_a);

} // namespace tissuemesh::fem

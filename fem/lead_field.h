// EEG and MEG lead fields by the transfer-matrix (reciprocity) approach: one FE solve per electrode (against a
// reference) and per MEG sensor, with the AMG hierarchy set up once for all of them; then the lead field of
// any number of sources is a product with their loads, without a solve per source (Wolters et al. 2004,
// Drechsler et al. 2009, as DUNEuro does it; used by FieldTrip and Brainstorm).
//
// The system is K u = b with one node held at 0 V (the insulated body's potential is defined up to a
// constant, which average referencing and the MEG kernel, summing to zero, do not see). For an electrode e
// with surface interpolation r_e (project_onto_surface.h) and the reference electrode r0, the transfer row
// t_e solves K t_e = r_e - r0, so that the potential difference for loads b is t_e . b. An MEG sensor's field
// of the volume currents is c . u (magnetic_field.h), so its row solves K t = c, and the primary field is
// added per source. Dipole models: Venant and partial integration give sparse loads (the products cost
// next to nothing); subtraction gives a load over every node and a solve-free but full product per source.
//
// Units: positions mm, conductivities S/m; EEG V per A*m, MEG T per A*m.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/progress.h"
#include "core/tet_mesh.h"
#include "fem/conductivities.h"
#include "fem/magnetic_field.h"
#include "fem/project_onto_surface.h"
#include "fem/solve.h"
#include "fem/solve_potential.h"

namespace tissuemesh::fem {

/// An EEG electrode: a point on or near the scalp (projected onto the outer surface).
struct EegElectrode {
    Vec3 position_mm{};
    std::string name; ///< for messages ("Fp1 (eeg.csv line 3)"); empty: "electrode <n>"
};

/// A source position: three lead-field columns (unit moments along x, y, z) without an orientation, one
/// (the unit moment along it) with.
struct LeadFieldSource {
    Vec3 position_mm{};
    std::optional<Vec3> orientation; ///< unit vector
    std::string name;                ///< for messages; empty: "source <n>"
};

/// Settings of compute_lead_fields(). Lengths in mm.
struct LeadFieldOptions {
    /// Venant: the most accurate of our models on our meshes at the eccentricities EEG sources have
    /// (docs/fem.md, accuracy); subtraction costs a pass over the mesh per source column.
    DipoleModel dipole_model = DipoleModel::venant;
    VenantOptions venant;                           ///< used only with DipoleModel::venant
    std::vector<Label> source_tissues;              ///< sources must lie in these tissues (empty: any)
    double max_electrode_distance_mm = 10;          ///< electrodes farther from the surface are refused
    double min_meg_distance_mm = 1;                 ///< MEG coils nearer the surface (or inside) are refused
    std::optional<std::size_t> reference_electrode; ///< EEG against this electrode; none: average reference
    VolumeCurrentOptions meg;                       ///< the volume-current integral
    /// For every solve. A relative residual of 1e-6 moved the EEG lead field of the 62 k-node 4-shell test head by
    /// at most 3.9e-5 per column (median 7e-6) from its value at 1e-10, and MEG by 3.5e-7, far below the
    /// discretisation's 1e-2; 1e-8 takes about 40% more iterations (16-17 against 11-13 there).
    SolverOptions solver{.relative_tolerance = 1e-6};
};

/// What compute_lead_fields() did.
struct LeadFieldReport {
    std::size_t unknowns = 0;   ///< free nodes of the system
    std::size_t solves = 0;     ///< right-hand sides: electrodes - 1 + MEG sensors
    std::size_t columns = 0;    ///< lead-field columns (3 per free source, 1 per oriented one)
    std::size_t load_nodes = 0; ///< nodes the source loads touch (the transfer rows kept)
    ColumnsReport solver;
    std::vector<SurfacePoint> electrodes; ///< where each electrode went (nodes numbered as the mesh's)
    std::vector<Label> source_tissues;    ///< the tissue each source lies in
    double assembly_seconds = 0;          ///< renumbering, stiffness matrix, reduction
    double sources_seconds = 0;           ///< locating the sources and their loads
    double sensors_seconds = 0;           ///< electrode projection and sensor checks
    double products_seconds = 0;          ///< subtraction's per-source loads and products (0 otherwise)
};

/// The lead fields: row per sensor, column per source column (source order; x, y, z for free sources).
struct LeadFields {
    using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    Matrix eeg; ///< V per A*m (#electrodes rows, or none); average reference unless a reference electrode is set
    Matrix meg; ///< T per A*m (#MEG sensors rows, or none): primary plus volume currents
};

/// The EEG and MEG lead fields of `sources` at `electrodes` and `meg_sensors` (either may be empty, not both).
/// @throws InputError when there is no sensor or no source, fewer than 2 electrodes, the reference electrode is
///         out of range, an electrode lies farther than max_electrode_distance_mm from the surface, an MEG
///         coil lies inside the mesh or nearer it than min_meg_distance_mm, a source lies outside the mesh or
///         in a tissue not in source_tissues, or the dipole model cannot take a source (subtraction in an
///         anisotropic tissue or on a node); each names the sensor or source
/// @throws AlgorithmError when a solve does not converge (see solve_spd_columns)
LeadFields compute_lead_fields(const TetMesh& mesh, const Conductivities& conductivities,
                               const std::vector<EegElectrode>& electrodes, const std::vector<MegSensor>& meg_sensors,
                               const std::vector<LeadFieldSource>& sources, const LeadFieldOptions& options = {},
                               const Progress& progress = {}, LeadFieldReport* report = nullptr);

} // namespace tissuemesh::fem

// What tm-solve reports about a potential: the fields per tet, their statistics per tissue, the error
// indicator and the mesh's smallest angle.
#pragma once

#include <cstddef>
#include <map>
#include <vector>

#include "core/tet_mesh.h"
#include "fem/compute_fields.h"
#include "fem/conductivities.h"

namespace tissuemesh::fem {

/// Options for analyse_solution().
struct AnalysisOptions {
    bool error_indicator = false; ///< also compute estimate_error()'s flux-jump indicator per tet
};

/// The fields of one tissue, weighted by tet volume.
struct TissueFieldStatistics {
    std::size_t tets = 0;
    double volume_mm3 = 0;
    double mean_e_v_per_m = 0;  ///< volume-weighted mean |E|
    double max_e_v_per_m = 0;   ///< largest |E| of a tet
    double mean_j_a_per_m2 = 0; ///< volume-weighted mean |J|
};

/// Time a part of analyse_solution() took: wall seconds, and CPU seconds of the process (all threads).
struct PartSeconds {
    double wall = 0, cpu = 0;
};

/// What analyse_solution() found. Per-tet arrays have #T entries, indexed like mesh.tets.
struct SolutionAnalysis {
    TetFields fields;                                               ///< E and J per tet (compute_fields)
    std::vector<double> e_magnitude_v_per_m;                        ///< |E| per tet
    std::vector<double> error_indicator;                            ///< eta per tet; empty unless asked for
    double error_indicator_total = 0;                               ///< sqrt(sum eta^2); 0 unless asked for
    std::map<Label, TissueFieldStatistics> tissues;                 ///< every tissue of the mesh
    double min_dihedral_deg = 180;                                  ///< smallest dihedral angle (slivers slow CG down)
    PartSeconds fields_time, error_indicator_time, statistics_time; ///< what each part took
};

/// The fields of nodal potentials `potential_v` (#V, V) and what tm-solve reports about them. Runs on every
/// core; the results do not depend on the thread count.
/// @throws InputError as compute_fields()
SolutionAnalysis analyse_solution(const TetMesh& mesh, const Conductivities& conductivities,
                                  const std::vector<double>& potential_v, const AnalysisOptions& options = {});

} // namespace tissuemesh::fem

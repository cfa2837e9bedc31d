#include "fem/solve_potential.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

#include "core/error.h"
#include "fem/assemble.h"
#include "fem/detail/local_stiffness.h"
#include "fem/detail/locality_order.h"
#include "fem/detail/reduce.h"
#include "fem/detail/sources.h"
#include "fem/detail/subtraction.h"
#include "fem/detail/venant.h"
#include "fem/outer_boundary.h"

namespace tissuemesh::fem {
namespace {

constexpr double unset = std::numeric_limits<double>::quiet_NaN();

// Fixes node `node` (numbered as in `mesh`) of the renumbered mesh to `value`; messages name the caller's
// node numbers.
void fix_node(const detail::LocalMesh& mesh, std::vector<double>& fixed, std::uint32_t node, double value,
              const std::string& what)
{
    const std::uint32_t shown = mesh.original[node];
    if (!std::isfinite(value)) throw InputError(concat(what, ": potential of node ", shown, " is not finite"));
    if (!std::isnan(fixed[node]) && fixed[node] != value)
        throw InputError(concat(what, ": node ", shown, " is fixed at both ", fixed[node], " V and ", value,
                                " V; electrodes and fixed potentials must not overlap"));
    fixed[node] = value;
}

// The renumbered index of the caller's node `node`.
std::uint32_t local_node(const detail::LocalMesh& mesh, std::uint32_t node, const std::string& what)
{
    if (node >= mesh.local.size())
        throw InputError(
            concat(what, ": node ", node, " is out of range (the mesh has ", mesh.local.size(), " nodes)"));
    return mesh.local[node];
}

// Loads (A) of current electrodes and dipoles; fixed potentials (NaN: free) of the others.
Eigen::VectorXd build_loads(const detail::LocalMesh& local, const Conductivities& conductivities,
                            const PotentialProblem& problem, std::vector<double>& fixed, PotentialReport& report,
                            std::vector<detail::SubtractionSource>& subtracted)
{
    const TetMesh& mesh = local.mesh;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(mesh.vertex_count()));
    if (problem.fixed.nodes.size() != problem.fixed.values_v.size())
        throw InputError(concat("fixed potentials: ", problem.fixed.nodes.size(), " nodes but ",
                                problem.fixed.values_v.size(), " values; give one value per node"));
    for (std::size_t k = 0; k < problem.fixed.nodes.size(); ++k)
        fix_node(local, fixed, local_node(local, problem.fixed.nodes[k], "fixed potentials"), problem.fixed.values_v[k],
                 "fixed potentials");
    // The whole outer boundary (a face-neighbour pass over every tet, 1.7 s for 6.2 M tets) for the
    // subtraction approach, which integrates over it, and for many electrodes; a few electrodes take only the
    // part under each (a pass over the nodes and tets, but no face pairing: 0.05 s each there).
    constexpr std::size_t few_electrodes = 8;
    const bool needs_boundary = (!problem.dipoles.empty() && problem.dipole_model == DipoleModel::subtraction) ||
                                problem.electrodes.size() > few_electrodes;
    const OuterBoundary boundary = needs_boundary ? outer_boundary(mesh) : OuterBoundary{};
    double injected = 0;
    double injected_magnitude = 0;
    for (std::size_t e = 0; e < problem.electrodes.size(); ++e) {
        const Electrode& electrode = problem.electrodes[e];
        // Both branches name an lvalue: the whole boundary is not copied per electrode.
        const OuterBoundary near =
            needs_boundary ? OuterBoundary{} : outer_boundary_near(mesh, electrode.centre_mm, electrode.radius_mm);
        const detail::ElectrodePatch patch =
            detail::electrode_patch(mesh, needs_boundary ? boundary : near, electrode, e);
        report.electrode_nodes.push_back(patch.nodes.size());
        report.electrode_area_mm2.push_back(patch.area_mm2);
        for (std::size_t k = 0; k < patch.nodes.size(); ++k) {
            if (electrode.mode == Electrode::Mode::potential)
                fix_node(local, fixed, patch.nodes[k], electrode.potential_v, detail::electrode_label(electrode, e));
            else rhs[patch.nodes[k]] += electrode.current_a * patch.node_area_mm2[k] / patch.area_mm2;
        }
        if (electrode.mode == Electrode::Mode::current) {
            injected += electrode.current_a;
            injected_magnitude += std::abs(electrode.current_a);
        }
    }
    for (std::size_t d = 0; d < problem.dipoles.size(); ++d) {
        if (problem.dipole_model == DipoleModel::partial_integration) {
            detail::add_dipole_load(mesh, problem.dipoles[d], d, rhs);
        } else if (problem.dipole_model == DipoleModel::venant) {
            detail::add_venant_load(mesh, conductivities, problem.dipoles[d], d, problem.venant, rhs);
        } else {
            subtracted.push_back(detail::subtraction_source(mesh, conductivities, problem.dipoles[d], d));
            detail::add_subtraction_load(mesh, conductivities, boundary, subtracted.back(), rhs);
        }
    }
    const bool anything_fixed = std::any_of(fixed.begin(), fixed.end(), [](double v) { return !std::isnan(v); });
    // Insulated body: the current that goes in must come out (1e-9 relative: round-off of user input).
    if (!anything_fixed && std::abs(injected) > 1e-9 * injected_magnitude)
        throw InputError(concat("electrode currents sum to ", injected, " A; with an insulated boundary and no fixed ",
                                "potential they must sum to zero: add a return electrode"));
    return rhs;
}

double seconds_since(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

std::vector<double> solve_potential(const TetMesh& mesh, const Conductivities& conductivities,
                                    const PotentialProblem& problem, const SolverOptions& options,
                                    const Progress& progress, PotentialReport* report)
{
    auto start = std::chrono::steady_clock::now();
    PotentialReport local;
    validate_indices(mesh, "mesh");
    // Everything runs on a copy numbered for locality; the potentials go back to the caller's numbering.
    const detail::LocalMesh renumbered = detail::renumber_for_locality(mesh);
    // Assembly first: it checks every tet and tissue, which the parallel source loops rely on. A bad tet
    // is reported as the caller numbers it: the original mesh is assembled again to throw its message.
    SparseMatrix stiffness = detail::assemble_local_stiffness(mesh, renumbered, conductivities);
    local.assembly_seconds = seconds_since(start);
    start = std::chrono::steady_clock::now();
    std::vector<double> fixed(mesh.vertex_count(), unset);
    std::vector<detail::SubtractionSource> subtracted;
    const Eigen::VectorXd rhs = build_loads(renumbered, conductivities, problem, fixed, local, subtracted);
    const bool anything_fixed = std::any_of(fixed.begin(), fixed.end(), [](double v) { return !std::isnan(v); });
    // Pure Neumann: the loads sum to zero, so fixing one node to 0 V picks one solution out of the
    // constants; zero_mean then shifts it.
    if (!anything_fixed && !fixed.empty()) {
        const std::uint32_t node = problem.reference == Reference::node ? problem.reference_node : 0;
        fix_node(renumbered, fixed, local_node(renumbered, node, "reference node"), 0.0, "reference node");
    }
    // With subtraction the unknown is the correction: fixed nodes hold their potential minus phi_inf.
    std::vector<double> singular(subtracted.empty() ? 0 : fixed.size(), 0.0);
    for (const detail::SubtractionSource& source : subtracted)
        for (std::size_t i = 0; i < singular.size(); ++i)
            singular[i] += detail::unbounded_potential(source, renumbered.mesh.vertices[i]);
    std::vector<double> fixed_correction(fixed);
    for (std::size_t i = 0; i < singular.size(); ++i) fixed_correction[i] -= singular[i];
    local.loads_seconds = seconds_since(start);
    start = std::chrono::steady_clock::now();
    detail::ReducedSystem system = detail::reduce(stiffness, rhs, fixed_correction, renumbered.mesh.vertices);
    stiffness = SparseMatrix();
    local.reduction_seconds = seconds_since(start);
    const Eigen::VectorXd solution = solve_spd(system.matrix, system.rhs, options, progress, &local.solver);
    std::vector<double> potential(fixed.size());
    for (std::size_t i = 0; i < potential.size(); ++i) {
        const std::uint32_t k = renumbered.local[i];
        potential[i] =
            system.free_index[k] < 0 ? fixed[k] : solution[system.free_index[k]] + (singular.empty() ? 0 : singular[k]);
    }
    local.unknowns = static_cast<std::size_t>(system.matrix.rows());
    local.fixed_nodes = fixed.size() - local.unknowns;
    if (!anything_fixed && problem.reference == Reference::zero_mean && !potential.empty()) {
        double mean = 0;
        for (double value : potential) mean += value;
        mean /= static_cast<double>(potential.size());
        for (double& value : potential) value -= mean;
    }
    if (report) *report = std::move(local);
    return potential;
}

} // namespace tissuemesh::fem

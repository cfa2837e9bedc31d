#include "fem/solve_potential.h"

#include <cmath>
#include <limits>

#include "core/error.h"
#include "fem/assemble.h"
#include "fem/detail/sources.h"
#include "fem/outer_boundary.h"

namespace tissuemesh::fem {
namespace {

constexpr double unset = std::numeric_limits<double>::quiet_NaN();

void fix_node(std::vector<double>& fixed, std::uint32_t node, double value, const std::string& what)
{
    if (node >= fixed.size())
        throw InputError(concat(what, ": node ", node, " is out of range (the mesh has ", fixed.size(), " nodes)"));
    if (!std::isfinite(value)) throw InputError(concat(what, ": potential of node ", node, " is not finite"));
    if (!std::isnan(fixed[node]) && fixed[node] != value)
        throw InputError(concat(what, ": node ", node, " is fixed at both ", fixed[node], " V and ", value,
                                " V; electrodes and fixed potentials must not overlap"));
    fixed[node] = value;
}

// Loads (A) of current electrodes and dipoles; fixed potentials (NaN: free) of the others.
Eigen::VectorXd build_loads(const TetMesh& mesh, const PotentialProblem& problem, std::vector<double>& fixed,
                            PotentialReport& report)
{
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(mesh.vertex_count()));
    if (problem.fixed.nodes.size() != problem.fixed.values_v.size())
        throw InputError(concat("fixed potentials: ", problem.fixed.nodes.size(), " nodes but ",
                                problem.fixed.values_v.size(), " values; give one value per node"));
    for (std::size_t k = 0; k < problem.fixed.nodes.size(); ++k)
        fix_node(fixed, problem.fixed.nodes[k], problem.fixed.values_v[k], "fixed potentials");
    const OuterBoundary boundary = outer_boundary(mesh);
    double injected = 0;
    double injected_magnitude = 0;
    for (std::size_t e = 0; e < problem.electrodes.size(); ++e) {
        const Electrode& electrode = problem.electrodes[e];
        const detail::ElectrodePatch patch = detail::electrode_patch(mesh, boundary, electrode, e);
        report.electrode_nodes.push_back(patch.nodes.size());
        report.electrode_area_mm2.push_back(patch.area_mm2);
        for (std::size_t k = 0; k < patch.nodes.size(); ++k) {
            if (electrode.mode == Electrode::Mode::potential)
                fix_node(fixed, patch.nodes[k], electrode.potential_v, concat("electrode ", e + 1));
            else
                rhs[patch.nodes[k]] += electrode.current_a * patch.node_area_mm2[k] / patch.area_mm2;
        }
        if (electrode.mode == Electrode::Mode::current) {
            injected += electrode.current_a;
            injected_magnitude += std::abs(electrode.current_a);
        }
    }
    for (std::size_t d = 0; d < problem.dipoles.size(); ++d) detail::add_dipole_load(mesh, problem.dipoles[d], d, rhs);
    const bool anything_fixed = std::any_of(fixed.begin(), fixed.end(), [](double v) { return !std::isnan(v); });
    // Insulated body: the current that goes in must come out (1e-9 relative: round-off of user input).
    if (!anything_fixed && std::abs(injected) > 1e-9 * injected_magnitude)
        throw InputError(concat("electrode currents sum to ", injected, " A; with an insulated boundary and no fixed ",
                                "potential they must sum to zero: add a return electrode"));
    return rhs;
}

// Reduced system on the free nodes: K_FF x_F = b_F - K_FD x_D.
std::vector<double> solve_reduced(const SparseMatrix& stiffness, const Eigen::VectorXd& rhs,
                                  const std::vector<double>& fixed, const SolverOptions& options,
                                  const Progress& progress, PotentialReport& report)
{
    const auto n = static_cast<int>(fixed.size());
    std::vector<int> free_index(fixed.size(), -1);
    int free_count = 0;
    for (int i = 0; i < n; ++i)
        if (std::isnan(fixed[i])) free_index[i] = free_count++;
    std::vector<Eigen::Triplet<double, int>> triplets;
    Eigen::VectorXd reduced_rhs(free_count);
    for (int row = 0; row < n; ++row) {
        if (free_index[row] < 0) continue;
        double value = rhs[row];
        for (SparseMatrix::InnerIterator entry(stiffness, row); entry; ++entry) {
            if (free_index[entry.col()] >= 0)
                triplets.emplace_back(free_index[row], free_index[entry.col()], entry.value());
            else
                value -= entry.value() * fixed[entry.col()];
        }
        reduced_rhs[free_index[row]] = value;
    }
    SparseMatrix reduced(free_count, free_count);
    reduced.setFromTriplets(triplets.begin(), triplets.end());
    const Eigen::VectorXd solution = solve_spd(reduced, reduced_rhs, options, progress, &report.solver);
    std::vector<double> potential(fixed);
    for (int i = 0; i < n; ++i)
        if (free_index[i] >= 0) potential[i] = solution[free_index[i]];
    report.unknowns = static_cast<std::size_t>(free_count);
    report.fixed_nodes = fixed.size() - report.unknowns;
    return potential;
}

} // namespace

std::vector<double> solve_potential(const TetMesh& mesh, const Conductivities& conductivities,
                                    const PotentialProblem& problem, const SolverOptions& options,
                                    const Progress& progress, PotentialReport* report)
{
    const SparseMatrix stiffness = assemble_stiffness(mesh, conductivities);
    PotentialReport local;
    std::vector<double> fixed(mesh.vertex_count(), unset);
    const Eigen::VectorXd rhs = build_loads(mesh, problem, fixed, local);
    const bool anything_fixed = std::any_of(fixed.begin(), fixed.end(), [](double v) { return !std::isnan(v); });
    // Pure Neumann: the loads sum to zero, so fixing one node to 0 V picks one solution out of the
    // constants; zero_mean then shifts it.
    if (!anything_fixed && !fixed.empty()) {
        const std::uint32_t node = problem.reference == Reference::node ? problem.reference_node : 0;
        fix_node(fixed, node, 0.0, "reference node");
    }
    std::vector<double> potential = solve_reduced(stiffness, rhs, fixed, options, progress, local);
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

#include "fem/tdcs_lead_field.h"

#include <chrono>
#include <cmath>

#include "core/error.h"
#include "fem/assemble.h"
#include "fem/detail/local_stiffness.h"
#include "fem/detail/locality_order.h"
#include "fem/detail/reduce.h"
#include "fem/detail/sources.h"
#include "fem/outer_boundary.h"

namespace tissuemesh::fem {

TdcsLeadField compute_tdcs_lead_field(const TetMesh& mesh, const Conductivities& conductivities,
                                      const std::vector<Electrode>& electrodes, std::size_t reference,
                                      const SolverOptions& options, const Progress& progress,
                                      TdcsLeadFieldReport* report)
{
    if (electrodes.size() < 2)
        throw InputError(concat("tDCS lead field: ", electrodes.size(), " electrode(s); a current needs at least 2"));
    if (reference >= electrodes.size())
        throw InputError(concat("tDCS lead field: reference electrode ", reference + 1, " of ", electrodes.size(),
                                " does not exist"));
    const auto start = std::chrono::steady_clock::now();
    TdcsLeadFieldReport local;
    validate_indices(mesh, "mesh");
    const detail::LocalMesh renumbered = detail::renumber_for_locality(mesh);
    const TetMesh& m = renumbered.mesh;
    SparseMatrix stiffness = detail::assemble_local_stiffness(mesh, renumbered, conductivities);
    std::vector<double> fixed(m.vertex_count(), std::nan(""));
    fixed[renumbered.local[0]] = 0; // one node at 0 V, as solve_potential() holds; each row gets zero mean at the end
    const detail::ReducedSystem system = detail::reduce(stiffness, {}, fixed, m.vertices);
    stiffness = SparseMatrix();
    const OuterBoundary boundary = outer_boundary(m);
    std::vector<detail::ElectrodePatch> patches;
    for (std::size_t e = 0; e < electrodes.size(); ++e) {
        patches.push_back(detail::electrode_patch(m, boundary, electrodes[e], e));
        local.electrode_nodes.push_back(patches.back().nodes.size());
        local.electrode_area_mm2.push_back(patches.back().area_mm2);
    }
    local.assembly_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    TdcsLeadField lead_field;
    lead_field.reference = reference;
    for (std::size_t e = 0; e < electrodes.size(); ++e)
        if (e != reference) lead_field.electrodes.push_back(e);
    lead_field.potentials_v_per_a.resize(static_cast<Eigen::Index>(lead_field.electrodes.size()),
                                         static_cast<Eigen::Index>(mesh.vertex_count()));
    const auto add_patch = [&](const detail::ElectrodePatch& patch, double current, Eigen::VectorXd& b) {
        for (std::size_t k = 0; k < patch.nodes.size(); ++k)
            if (const int row = system.free_index[patch.nodes[k]]; row >= 0)
                b[row] += current * patch.node_area_mm2[k] / patch.area_mm2;
    };
    const auto rhs = [&](std::size_t k, Eigen::VectorXd& b) {
        add_patch(patches[lead_field.electrodes[k]], 1, b);
        add_patch(patches[reference], -1, b);
    };
    const auto sink = [&](std::size_t k, const double* values) {
        const auto row = static_cast<Eigen::Index>(k);
        double mean = 0;
        for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
            const int free = system.free_index[renumbered.local[i]];
            const double value = free < 0 ? 0.0 : values[free];
            lead_field.potentials_v_per_a(row, static_cast<Eigen::Index>(i)) = value;
            mean += value;
        }
        lead_field.potentials_v_per_a.row(row).array() -= mean / static_cast<double>(mesh.vertex_count());
    };
    solve_spd_columns(system.matrix, lead_field.electrodes.size(), rhs, {}, sink, options, progress, &local.solver);
    if (report) *report = std::move(local);
    return lead_field;
}

std::vector<double> montage_potential(const TdcsLeadField& lead_field, const std::vector<double>& currents_a)
{
    const std::size_t count = lead_field.electrodes.size() + 1;
    if (currents_a.size() != count)
        throw InputError(
            concat("montage: ", currents_a.size(), " currents for a lead field of ", count, " electrodes"));
    double sum = 0, magnitude = 0;
    for (const double current : currents_a) {
        if (!std::isfinite(current)) throw InputError("montage: a current is not finite");
        sum += current;
        magnitude += std::abs(current);
    }
    if (std::abs(sum) > 1e-9 * magnitude)
        throw InputError(
            concat("montage: the currents sum to ", sum, " A; what goes in must come out: make them ", "sum to zero"));
    Eigen::RowVectorXd potential = Eigen::RowVectorXd::Zero(lead_field.potentials_v_per_a.cols());
    for (std::size_t k = 0; k < lead_field.electrodes.size(); ++k)
        potential +=
            currents_a[lead_field.electrodes[k]] * lead_field.potentials_v_per_a.row(static_cast<Eigen::Index>(k));
    return {potential.data(), potential.data() + potential.size()};
}

} // namespace tissuemesh::fem

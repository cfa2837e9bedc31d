#include "fem/lead_field.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "fem/assemble.h"
#include "fem/detail/lead_field_sources.h"
#include "fem/detail/local_stiffness.h"
#include "fem/detail/locality_order.h"
#include "fem/detail/point_location.h"
#include "fem/detail/reduce.h"
#include "fem/detail/subtraction.h"
#include "fem/outer_boundary.h"

namespace tissuemesh::fem {
namespace {

using Clock = std::chrono::steady_clock;
using Matrix = LeadFields::Matrix;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::string sensor_label(const MegSensor& sensor, std::size_t index)
{
    return sensor.name.empty() ? concat("MEG sensor ", index + 1) : sensor.name;
}

void check_request(const std::vector<EegElectrode>& electrodes, const std::vector<MegSensor>& meg_sensors,
                   const std::vector<LeadFieldSource>& sources, const LeadFieldOptions& options)
{
    if (electrodes.empty() && meg_sensors.empty())
        throw InputError("lead field: no EEG electrode and no MEG sensor; give at least one kind of sensor");
    if (electrodes.size() == 1)
        throw InputError("lead field: one EEG electrode measures no potential difference; give at least 2");
    if (sources.empty()) throw InputError("lead field: no source; give at least one source position");
    if (options.reference_electrode && *options.reference_electrode >= electrodes.size())
        throw InputError(concat("lead field: reference electrode ", *options.reference_electrode + 1, " of ",
                                electrodes.size(), " electrodes does not exist"));
    if (!(options.max_electrode_distance_mm >= 0) || !(options.min_meg_distance_mm >= 0))
        throw InputError("lead field: the electrode and MEG sensor distances must be lengths of 0 mm or more");
}

// MEG coils must be outside the head, and not on its surface (the volume-current integral is near-singular
// there).
void check_meg_sensors(const TetMesh& mesh, const OuterBoundary& boundary, const std::vector<MegSensor>& sensors,
                       double min_distance_mm)
{
    std::vector<Vec3> coils;
    std::vector<std::size_t> owner;
    for (std::size_t s = 0; s < sensors.size(); ++s) {
        coils.push_back(sensors[s].position_mm), owner.push_back(s);
        if (sensors[s].second_coil_mm) coils.push_back(*sensors[s].second_coil_mm), owner.push_back(s);
    }
    const std::vector<std::uint32_t> inside = detail::locate_points(mesh, coils);
    const std::vector<SurfacePoint> nearest =
        project_onto_surface(mesh, boundary, coils, {}, std::numeric_limits<double>::infinity());
    for (std::size_t c = 0; c < coils.size(); ++c) {
        const bool within = inside[c] != detail::outside_mesh;
        if (!within && nearest[c].distance_mm >= min_distance_mm) continue;
        const Vec3& p = coils[c];
        throw InputError(concat(
            sensor_label(sensors[owner[c]], owner[c]), " has a coil at (", format_mm(p[0]), ", ", format_mm(p[1]), ", ",
            format_mm(p[2]), ") mm ",
            within ? "inside the head" : concat(format_mm(nearest[c].distance_mm), " mm from the head's surface"),
            "; MEG coils must be outside the head, at least ", format_mm(min_distance_mm),
            " mm from it: check the units (mm) and that the sensors are in the mesh's coordinates"));
    }
}

// The sparse loads of every column in the system's rows, and the rows they touch (the transfer rows kept).
struct KeptLoads {
    std::vector<std::uint32_t> rows;             ///< increasing system rows
    std::vector<std::vector<std::uint32_t>> at;  ///< per column: positions in `rows`
    std::vector<std::vector<double>> currents_a; ///< per column, parallel to `at`
};

KeptLoads keep_loads(const std::vector<detail::ColumnLoad>& loads, const std::vector<int>& free_index)
{
    KeptLoads kept;
    for (const detail::ColumnLoad& load : loads)
        for (const std::uint32_t node : load.nodes)
            if (free_index[node] >= 0) kept.rows.push_back(static_cast<std::uint32_t>(free_index[node]));
    std::sort(kept.rows.begin(), kept.rows.end());
    kept.rows.erase(std::unique(kept.rows.begin(), kept.rows.end()), kept.rows.end());
    for (const detail::ColumnLoad& load : loads) {
        std::vector<std::uint32_t> at;
        std::vector<double> currents;
        for (std::size_t k = 0; k < load.nodes.size(); ++k) {
            const int row = free_index[load.nodes[k]];
            if (row < 0) continue; // the node held at 0 V: its load does no work
            at.push_back(static_cast<std::uint32_t>(
                std::lower_bound(kept.rows.begin(), kept.rows.end(), static_cast<std::uint32_t>(row)) -
                kept.rows.begin()));
            currents.push_back(load.currents_a[k]);
        }
        kept.at.push_back(std::move(at));
        kept.currents_a.push_back(std::move(currents));
    }
    return kept;
}

// Adds `weight` times the surface interpolation of `point` to b (system rows).
void add_point(const SurfacePoint& point, double weight, const std::vector<int>& free_index, Eigen::VectorXd& b)
{
    for (int k = 0; k < 3; ++k)
        if (const int row = free_index[point.nodes[static_cast<std::size_t>(k)]]; row >= 0)
            b[row] += weight * point.weights[static_cast<std::size_t>(k)];
}

double interpolate(const SurfacePoint& point, const std::vector<double>& values)
{
    return point.weights[0] * values[point.nodes[0]] + point.weights[1] * values[point.nodes[1]] +
           point.weights[2] * values[point.nodes[2]];
}

// Subtraction: each column's correction load over every node, and the singular potential's share of the
// sensors' values; `transfer` holds a row per solve over every system row, `kernels` the MEG kernels.
void subtraction_products(const TetMesh& mesh, const Conductivities& conductivities,
                          const std::vector<LeadFieldSource>& sources, const std::vector<std::uint32_t>& tets,
                          const detail::ReducedSystem& system, const Matrix& transfer,
                          const std::vector<SurfacePoint>& electrodes, const std::vector<std::size_t>& solve_electrodes,
                          std::size_t reference, const std::vector<std::vector<double>>& kernels,
                          const Progress& progress, Matrix& raw)
{
    const OuterBoundary boundary = outer_boundary(mesh);
    ProgressTicker ticker(progress, "leadfield", sources.size());
    Eigen::VectorXd load(static_cast<Eigen::Index>(mesh.vertex_count())), free_load(transfer.cols());
    std::vector<double> singular(mesh.vertex_count());
    Eigen::Index column = 0;
    for (std::size_t s = 0; s < sources.size(); ++s) {
        for (const Vec3& moment : detail::column_moments(sources[s])) {
            const detail::SubtractionSource source =
                detail::subtraction_source_in(mesh, conductivities, {sources[s].position_mm, moment}, s, tets[s]);
            load.setZero();
            detail::add_subtraction_load(mesh, conductivities, boundary, source, load);
            for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
                singular[i] = detail::unbounded_potential(source, mesh.vertices[i]);
                if (system.free_index[i] >= 0) free_load[system.free_index[i]] = load[static_cast<Eigen::Index>(i)];
            }
            raw.col(column) = transfer * free_load;
            for (std::size_t k = 0; k < solve_electrodes.size(); ++k)
                raw(static_cast<Eigen::Index>(k), column) += interpolate(electrodes[solve_electrodes[k]], singular) -
                                                             interpolate(electrodes[reference], singular);
            for (std::size_t j = 0; j < kernels.size(); ++j) {
                double field = 0;
                for (std::size_t i = 0; i < singular.size(); ++i) field += kernels[j][i] * singular[i];
                raw(static_cast<Eigen::Index>(solve_electrodes.size() + j), column) += field;
            }
            ++column;
        }
        ticker.step();
    }
}

} // namespace

LeadFields compute_lead_fields(const TetMesh& mesh, const Conductivities& conductivities,
                               const std::vector<EegElectrode>& electrodes, const std::vector<MegSensor>& meg_sensors,
                               const std::vector<LeadFieldSource>& sources, const LeadFieldOptions& options,
                               const Progress& progress, LeadFieldReport* report)
{
    check_request(electrodes, meg_sensors, sources, options);
    LeadFieldReport local;
    auto start = Clock::now();
    validate_indices(mesh, "mesh");
    // Everything runs on a copy numbered for locality (as solve_potential does).
    const detail::LocalMesh renumbered = detail::renumber_for_locality(mesh);
    const TetMesh& m = renumbered.mesh;
    SparseMatrix stiffness = detail::assemble_local_stiffness(mesh, renumbered, conductivities);
    // The node held at 0 V is solve_potential()'s, the caller's node 0: subtraction's loads carry a net current
    // of quadrature error, which that node takes up (holding another node moved the EEG lead field of the small
    // test head by 1.6e-4, relative), so the same node gives the same potentials as direct solves.
    std::vector<double> fixed(m.vertex_count(), std::nan(""));
    fixed[renumbered.local[0]] = 0;
    const detail::ReducedSystem system = detail::reduce(stiffness, {}, fixed, m.vertices);
    stiffness = SparseMatrix();
    local.unknowns = static_cast<std::size_t>(system.matrix.rows());
    local.assembly_seconds = seconds_since(start);

    start = Clock::now();
    const OuterBoundary boundary = outer_boundary(m);
    std::vector<Vec3> positions;
    std::vector<std::string> names;
    for (const EegElectrode& electrode : electrodes)
        positions.push_back(electrode.position_mm), names.push_back(electrode.name);
    const std::vector<SurfacePoint> on_surface =
        electrodes.empty() ? std::vector<SurfacePoint>{}
                           : project_onto_surface(m, boundary, positions, names, options.max_electrode_distance_mm);
    if (!meg_sensors.empty()) check_meg_sensors(m, boundary, meg_sensors, options.min_meg_distance_mm);
    local.sensors_seconds = seconds_since(start);

    start = Clock::now();
    const std::vector<std::uint32_t> tets = detail::locate_sources(m, sources, options.source_tissues);
    for (const std::uint32_t t : tets) local.source_tissues.push_back(m.tet_labels[t]);
    const bool subtraction = options.dipole_model == DipoleModel::subtraction;
    std::size_t columns = 0;
    for (const LeadFieldSource& source : sources) columns += source.orientation ? 1 : 3;
    KeptLoads kept;
    if (subtraction) {
        for (std::size_t s = 0; s < sources.size(); ++s) // refuse what subtraction cannot take before any solve
            detail::subtraction_source_in(m, conductivities, {sources[s].position_mm, Vec3{0, 0, 1}}, s, tets[s]);
    } else {
        kept = keep_loads(detail::column_loads(m, conductivities, sources, tets, options.dipole_model, options.venant),
                          system.free_index);
    }
    local.load_nodes = subtraction ? local.unknowns : kept.rows.size();
    local.sources_seconds = seconds_since(start);
    progress.info("leadfield",
                  concat(sources.size(), " sources located, ", columns, " lead-field columns, loads on ",
                         local.load_nodes, " nodes (", std::round(local.sources_seconds * 100) / 100, " s)"));

    // One solve per electrode but the reference, then one per MEG sensor.
    const std::size_t reference = options.reference_electrode.value_or(0);
    std::vector<std::size_t> solve_electrodes;
    for (std::size_t e = 0; e < electrodes.size(); ++e)
        if (e != reference) solve_electrodes.push_back(e);
    const std::size_t solves = solve_electrodes.size() + meg_sensors.size();
    local.solves = solves;
    local.columns = columns;
    Matrix raw = Matrix::Zero(static_cast<Eigen::Index>(solves), static_cast<Eigen::Index>(columns));
    Matrix transfer; // subtraction only: every system row of every solve
    if (subtraction) transfer.resize(static_cast<Eigen::Index>(solves), system.matrix.rows());
    std::vector<std::vector<double>> kernels; // subtraction only: the MEG kernels, for the singular potential
    const auto rhs = [&](std::size_t k, Eigen::VectorXd& b) {
        if (k < solve_electrodes.size()) {
            add_point(on_surface[solve_electrodes[k]], 1, system.free_index, b);
            add_point(on_surface[reference], -1, system.free_index, b);
            return;
        }
        std::vector<double> kernel =
            volume_current_kernel(m, conductivities, meg_sensors[k - solve_electrodes.size()], options.meg);
        for (std::size_t i = 0; i < kernel.size(); ++i)
            if (system.free_index[i] >= 0) b[system.free_index[i]] = kernel[i];
        if (subtraction && kernels.size() == k - solve_electrodes.size()) kernels.push_back(std::move(kernel));
    };
    const auto sink = [&](std::size_t k, const double* values) {
        const auto row = static_cast<Eigen::Index>(k);
        if (subtraction) {
            transfer.row(row) = Eigen::Map<const Eigen::RowVectorXd>(values, transfer.cols());
            return;
        }
        for (std::size_t c = 0; c < columns; ++c) {
            double sum = 0;
            for (std::size_t j = 0; j < kept.at[c].size(); ++j) sum += values[kept.at[c][j]] * kept.currents_a[c][j];
            raw(row, static_cast<Eigen::Index>(c)) = sum;
        }
    };
    solve_spd_columns(system.matrix, solves, rhs, subtraction ? std::vector<std::uint32_t>{} : kept.rows, sink,
                      options.solver, progress, &local.solver);
    if (subtraction) {
        start = Clock::now();
        subtraction_products(m, conductivities, sources, tets, system, transfer, on_surface, solve_electrodes,
                             reference, kernels, progress, raw);
        local.products_seconds = seconds_since(start);
    }

    LeadFields fields;
    if (!electrodes.empty()) {
        fields.eeg = Matrix::Zero(static_cast<Eigen::Index>(electrodes.size()), static_cast<Eigen::Index>(columns));
        for (std::size_t k = 0; k < solve_electrodes.size(); ++k)
            fields.eeg.row(static_cast<Eigen::Index>(solve_electrodes[k])) = raw.row(static_cast<Eigen::Index>(k));
        if (!options.reference_electrode) fields.eeg.rowwise() -= fields.eeg.colwise().mean();
    }
    if (!meg_sensors.empty()) {
        fields.meg = raw.bottomRows(static_cast<Eigen::Index>(meg_sensors.size()));
        Eigen::Index column = 0;
        for (const LeadFieldSource& source : sources)
            for (const Vec3& moment : detail::column_moments(source)) {
                for (std::size_t j = 0; j < meg_sensors.size(); ++j)
                    fields.meg(static_cast<Eigen::Index>(j), column) +=
                        primary_field(meg_sensors[j], {source.position_mm, moment});
                ++column;
            }
    }
    for (SurfacePoint point : on_surface) {
        for (std::uint32_t& node : point.nodes) node = renumbered.original[node];
        local.electrodes.push_back(point);
    }
    if (report) *report = std::move(local);
    return fields;
}

} // namespace tissuemesh::fem

// tm-solve: stationary current / electrostatics on a labelled tet mesh (P1 FEM, CG with BoomerAMG).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "fem/analyse_solution.h"
#include "fem/outer_boundary.h"
#include "fem/solve_potential.h"
#include "io/read_conductivity_table.h"
#include "io/read_electrodes.h"
#include "io/read_sensors.h"
#include "io/tet_mesh_io.h"
#include "io/write_vtu.h"
#include "tools/dipole_model.h"
#include "tools/lead_field_files.h"
#include "tools/run_tool.h"

using namespace tissuemesh;

namespace {

/// "1,2,3" -> {1, 2, 3}; exactly `count` finite numbers or InputError naming the flag.
std::vector<double> parse_numbers(const std::string& text, std::size_t count, const std::string& flag,
                                  const std::string& form)
{
    std::vector<double> values;
    std::stringstream items(text);
    for (std::string item; std::getline(items, item, ',');) {
        char* end = nullptr;
        const double value = std::strtod(item.c_str(), &end);
        if (item.empty() || *end != '\0' || !std::isfinite(value))
            throw InputError(concat(flag, " \"", text, "\": \"", item, "\" is not a number; write ", form));
        values.push_back(value);
    }
    if (values.size() != count)
        throw InputError(
            concat(flag, " \"", text, "\" has ", values.size(), " numbers, not ", count, "; write ", form));
    return values;
}

/// Potential at each sensor: the value at the nearest outer-boundary node. Named sensors keep their names.
std::string sensor_csv(const TetMesh& mesh, const std::vector<io::SensorRow>& sensors, const std::vector<double>& phi)
{
    const std::vector<std::uint32_t> surface = fem::outer_boundary(mesh).nodes;
    const bool named = !sensors.empty() && !sensors.front().name.empty();
    std::ostringstream out;
    out.precision(12);
    out << (named ? "name," : "") << "x,y,z,potential\n";
    for (const io::SensorRow& sensor : sensors) {
        const Vec3& s = sensor.position_mm;
        std::uint32_t best = surface.front();
        for (std::uint32_t node : surface)
            if (distance(mesh.vertices[node], s) < distance(mesh.vertices[best], s)) best = node;
        if (named) out << sensor.name << ',';
        out << s[0] << ',' << s[1] << ',' << s[2] << ',' << phi[best] << '\n';
    }
    return out.str();
}

/// Per-tissue tets, volume, volume-weighted mean and maximum |E| (V/m) and mean |J| (A/m^2), for --json.
nlohmann::json field_statistics(const TetMesh& mesh, const fem::SolutionAnalysis& analysis)
{
    nlohmann::json tissues = nlohmann::json::object();
    for (const auto& [label, t] : analysis.tissues) {
        const auto name = mesh.names.find(label);
        tissues[std::to_string(label)] = {{"tets", t.tets},
                                          {"volume_mm3", t.volume_mm3},
                                          {"mean_E_V_per_m", t.mean_e_v_per_m},
                                          {"max_E_V_per_m", t.max_e_v_per_m},
                                          {"mean_J_A_per_m2", t.mean_j_a_per_m2},
                                          {"name", name == mesh.names.end() ? std::to_string(label) : name->second}};
    }
    return tissues;
}

/// Seconds per phase of the run, for the --json summary: wall time, and the process's CPU time (all threads;
/// on a shared machine the CPU time says what a phase costs when the wall time mostly says how busy it was).
class PhaseClock {
public:
    void lap(const std::string& phase)
    {
        const auto now = std::chrono::steady_clock::now();
        const std::clock_t cpu_now = std::clock();
        phases_[phase] = std::chrono::duration<double>(now - last_).count();
        cpu_phases_[phase] = static_cast<double>(cpu_now - last_cpu_) / CLOCKS_PER_SEC;
        last_ = now;
        last_cpu_ = cpu_now;
    }
    void set(const std::string& phase, double seconds) { phases_[phase] = seconds; }
    void set(const std::string& phase, const fem::PartSeconds& part)
    {
        phases_[phase] = part.wall;
        cpu_phases_[phase] = part.cpu;
    }
    const nlohmann::json& phases() const { return phases_; }
    const nlohmann::json& cpu_phases() const { return cpu_phases_; }

private:
    std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
    std::clock_t last_cpu_ = std::clock();
    nlohmann::json phases_ = nlohmann::json::object(), cpu_phases_ = nlohmann::json::object();
};

/// The conductivities of the mesh's tissues from `table`, read from `path` (empty: the head defaults); errors
/// about the table's contents name the file.
fem::Conductivities resolve_from_file(const TetMesh& mesh, const fem::ConductivityTable& table, const std::string& path)
{
    if (path.empty()) return fem::resolve_conductivities(mesh, {});
    return tools::with_source(path, [&] { return fem::resolve_conductivities(mesh, table); });
}

/// The sources given on the command line: --dipole and --electrode flags, then the rows of --electrodes FILE
/// (each named in messages by its name and line).
fem::PotentialProblem parse_problem(const std::vector<std::string>& dipoles, const std::vector<std::string>& electrodes,
                                    const std::string& montage, const std::vector<io::ElectrodeRow>& montage_rows)
{
    fem::PotentialProblem problem;
    for (const std::string& text : dipoles) {
        const auto v = parse_numbers(text, 6, "--dipole", "X,Y,Z,PX,PY,PZ (mm, A*m)");
        problem.dipoles.push_back({{v[0], v[1], v[2]}, {v[3], v[4], v[5]}});
    }
    for (const std::string& text : electrodes) {
        const auto v = parse_numbers(text, 5, "--electrode", "X,Y,Z,RADIUS,CURRENT_A (mm, A)");
        if (!(v[3] > 0))
            throw InputError(concat("--electrode ", text, ": RADIUS ", v[3],
                                    " mm is not a positive length; write X,Y,Z,RADIUS,CURRENT_A (mm, A)"));
        problem.electrodes.push_back({.centre_mm = {v[0], v[1], v[2]},
                                      .radius_mm = v[3],
                                      .current_a = v[4],
                                      .name = concat("--electrode ", text)});
    }
    for (const io::ElectrodeRow& row : montage_rows)
        problem.electrodes.push_back(
            {.centre_mm = row.centre_mm,
             .radius_mm = row.radius_mm,
             .current_a = row.current_a,
             .name = concat(row.name.empty() ? "electrode" : row.name, " (", montage, " line ", row.line, ")")});
    if (problem.dipoles.empty() && problem.electrodes.empty())
        throw InputError(
            "no source: without --dipole, --electrode or --electrodes no current flows and the potential is "
            "zero everywhere; give at least one");
    return problem;
}

// Memory of a solve, the mesh it read included: 2.9-3.0 kB per node on TetGen meshes of spheres4 (0.23 and
// 0.56 M nodes, 5.5-6.1 tets per node; the matrix, its reduction, BoomerAMG's hierarchy, fields and .vtu),
// 2.1-2.3 kB on structured boxes (docs/robustness.md).
constexpr double bytes_per_node = 3000;

/// Refuses a solve that would need more memory than --max-memory allows, before the assembly.
void check_memory(const tools::ToolContext& context, const std::string& input, const TetMesh& mesh)
{
    const double nodes = static_cast<double>(mesh.vertex_count());
    tools::require_memory(context.memory, input, nodes * bytes_per_node,
                          concat(tools::format_count(nodes), " nodes x ", tools::format_bytes(bytes_per_node)),
                          "mesh it coarser (tm-tetra --max-volume)");
}

/// The solver's own phases (assembly, loads, AMG setup, CG) into `clock`.
void record_solver_phases(const fem::PotentialReport& report, PhaseClock& clock)
{
    clock.set("loads", report.loads_seconds);
    clock.set("assembly", report.assembly_seconds);
    clock.set("reduction", report.reduction_seconds);
    clock.set("solver_copy", report.solver.copy_seconds);
    clock.set("solver_setup", report.solver.setup_seconds);
    clock.set("solver_iterations", report.solver.iterate_seconds);
}

/// The potential of a montage from a tDCS lead field (tm-leadfield --tdcs-output): each montage electrode is
/// found in the lead field by name, at the patch it was computed for.
std::vector<double> potential_from_lead_field(const std::string& path, const TetMesh& mesh, const std::string& montage,
                                              const std::vector<io::ElectrodeRow>& rows)
{
    const tools::TdcsLeadFieldFile file = tools::read_tdcs_lead_field(path, mesh);
    std::vector<double> currents(file.names.size(), 0.0);
    for (const io::ElectrodeRow& row : rows) {
        const std::string where =
            concat(row.name.empty() ? "electrode" : row.name, " (", montage, " line ", row.line, ")");
        const auto found = std::find(file.names.begin(), file.names.end(), row.name);
        if (row.name.empty() || found == file.names.end())
            throw InputError(concat(where, ": not an electrode of the lead field ", path,
                                    "; name montage electrodes as ", "the lead field's (", file.names.size(),
                                    " of them, e.g. ", file.names.front(), ")"));
        const auto k = static_cast<std::size_t>(found - file.names.begin());
        // 1 micrometre: the same numbers written and read back, not another patch.
        if (distance(row.centre_mm, file.centres_mm[k]) > 1e-3 || std::abs(row.radius_mm - file.radii_mm[k]) > 1e-3)
            throw InputError(concat(where, ": a patch of ", format_mm(row.radius_mm), " mm at (",
                                    format_mm(row.centre_mm[0]), ", ", format_mm(row.centre_mm[1]), ", ",
                                    format_mm(row.centre_mm[2]), ") mm, but the lead field's ", row.name, " is ",
                                    format_mm(file.radii_mm[k]), " mm at (", format_mm(file.centres_mm[k][0]), ", ",
                                    format_mm(file.centres_mm[k][1]), ", ", format_mm(file.centres_mm[k][2]),
                                    ") mm; use its patches or compute the lead field again"));
        currents[k] = row.current_a;
    }
    return fem::montage_potential(file.lead_field, currents);
}

/// tm-solve's command line.
struct SolveFlags {
    std::string input, output, conductivity, sensors_path, sensor_output, montage, lead_field, solver = "amg",
                                                                                               dipole_model = "venant";
    std::vector<std::string> dipoles, electrodes;
    double tolerance = 1e-10;
    int processes = 0;
    bool error_indicator = false, vtu_ascii = false;

    void add_to(CLI::App& app)
    {
        app.add_option("-i,--input", input, "Tet mesh (.msh 2.2 or .mesh), mm")->required()->check(CLI::ExistingFile);
        app.add_option("-o,--output", output, "Solution .vtu: potential per node, E and J per tet")->required();
        app.add_option("--conductivity", conductivity, "JSON {tissue name or label: S/m or 3x3 tensor}");
        app.add_option("--dipole", dipoles, "X,Y,Z,PX,PY,PZ: position mm, moment A*m (repeatable)");
        app.add_option("--electrode", electrodes,
                       "X,Y,Z,RADIUS,CURRENT_A: scalp patch, current into the body (repeatable)");
        app.add_option("--electrodes", montage, "Montage CSV: x,y,z,radius_mm,current_a[,name] per electrode (mm, A)")
            ->type_name("FILE");
        app.add_option(
               "--leadfield", lead_field,
               "tDCS lead field of tm-leadfield (--tdcs-output): the --electrodes montage's field is summed from "
               "it without a solve (electrodes by name)")
            ->type_name("FILE")
            ->check(CLI::ExistingFile);
        app.add_option("--sensors", sensors_path, "CSV with header x,y,z[,name] (mm)")->type_name("FILE");
        app.add_option("--sensor-potentials", sensor_output,
                       "CSV out: [name,]x,y,z,potential (V) at the nearest surface node")
            ->type_name("FILE");
        app.add_option(
               "--dipole-model", dipole_model,
               "Dipole singularity: venant (the default: monopoles on the nearest node and its neighbours with the "
               "dipole's moments; any tissue, accurate up to the interfaces), subtraction (exact "
               "unbounded-medium potential plus a smooth correction; as accurate away from interfaces, needs "
               "an isotropic tissue at the source and a dipole off the nodes), or partial-integration (the "
               "load of the one tet that holds the dipole: several times less accurate, its error depends on "
               "that tet)")
            ->check(CLI::IsMember(tools::dipole_model_names));
        app.add_option("--solver", solver, "Preconditioner of CG: amg or jacobi")
            ->check(CLI::IsMember({"amg", "jacobi"}));
        app.add_option("--processes", processes,
                       "MPI processes for the AMG-CG (mpiexec; hypre has no threads here): 0 = one per available "
                       "core, 1 = none; fewer when each would get under 100 000 unknowns. The iteration count, and "
                       "so the last digits, depend on it")
            ->check(CLI::Range(0, 1024));
        app.add_option("--tolerance", tolerance, "Relative residual to reach (unitless)")->check(CLI::PositiveNumber);
        app.add_flag("--error-indicator", error_indicator,
                     "Also write the flux-jump error indicator per tet (error_indicator) and its total to --json");
        app.add_flag("--vtu-ascii", vtu_ascii, "Write the .vtu as ASCII instead of zlib-compressed binary");
    }
};

/// The potential: summed from --leadfield, or solved for the sources of the command line (the solver's phases
/// into `clock`, its figures into `report`).
std::vector<double> potential(const SolveFlags& flags, const TetMesh& mesh, const fem::Conductivities& sigma,
                              const std::vector<io::ElectrodeRow>& montage_rows, tools::ToolContext& context,
                              PhaseClock& clock, fem::PotentialReport& report)
{
    if (!flags.lead_field.empty()) {
        if (flags.montage.empty() || !flags.dipoles.empty() || !flags.electrodes.empty())
            throw InputError("--leadfield takes the montage from --electrodes FILE alone (no --dipole or --electrode)");
        std::vector<double> phi = potential_from_lead_field(flags.lead_field, mesh, flags.montage, montage_rows);
        clock.lap("solve");
        context.summary["lead_field"] = flags.lead_field;
        return phi;
    }
    fem::PotentialProblem problem = parse_problem(flags.dipoles, flags.electrodes, flags.montage, montage_rows);
    problem.dipole_model = tools::dipole_model_named(flags.dipole_model);
    std::vector<double> phi = fem::solve_potential(
        mesh, sigma, problem,
        {.preconditioner = flags.solver == "amg" ? fem::Preconditioner::amg : fem::Preconditioner::jacobi,
         .relative_tolerance = flags.tolerance,
         .processes = flags.processes},
        context.progress, &report);
    clock.lap("solve");
    record_solver_phases(report, clock);
    return phi;
}

/// The solution .vtu: the potential per node, E, J, |E| (and the error indicator) per tet.
void write_solution(const SolveFlags& flags, const TetMesh& mesh, const std::vector<double>& phi,
                    const fem::SolutionAnalysis& analysis)
{
    std::vector<io::VtuArray> cell_arrays{io::make_vtu_vectors("E_V_per_m", analysis.fields.electric_v_per_m),
                                          io::make_vtu_vectors("J_A_per_m2", analysis.fields.current_a_per_m2),
                                          io::make_vtu_array("E_magnitude_V_per_m", analysis.e_magnitude_v_per_m)};
    if (flags.error_indicator) cell_arrays.push_back(io::make_vtu_array("error_indicator", analysis.error_indicator));
    io::write_vtu(mesh, flags.output, {io::make_vtu_array("potential_V", phi)}, cell_arrays,
                  flags.vtu_ascii ? io::VtuEncoding::ascii : io::VtuEncoding::compressed);
}

/// The --json summary of a run.
void summarize(const TetMesh& mesh, const fem::PotentialReport& report, const fem::SolutionAnalysis& analysis,
               std::size_t sensors, bool error_indicator, const PhaseClock& clock, nlohmann::json& summary)
{
    if (error_indicator) summary["error_indicator_total"] = analysis.error_indicator_total;
    summary.update({{"tissues", field_statistics(mesh, analysis)},
                    {"min_dihedral_deg", analysis.min_dihedral_deg},
                    {"nodes", mesh.vertex_count()},
                    {"tets", mesh.tet_count()},
                    {"unknowns", report.unknowns},
                    {"preconditioner", report.solver.preconditioner},
                    {"processes", report.solver.processes},
                    {"iterations", report.solver.iterations},
                    {"relative_residual", report.solver.relative_residual},
                    {"solve_seconds", report.solver.seconds},
                    {"electrode_nodes", report.electrode_nodes},
                    {"electrode_area_mm2", report.electrode_area_mm2},
                    {"sensors", sensors},
                    {"phase_seconds", clock.phases()},
                    {"phase_cpu_seconds", clock.cpu_phases()}});
}

void run(const SolveFlags& flags, tools::ToolContext& context)
{
    if (flags.sensors_path.empty() != flags.sensor_output.empty())
        throw InputError("--sensors and --sensor-potentials go together; give both or neither");
    PhaseClock clock;
    // The small files first: a mistake in them is reported before the mesh is read.
    const fem::ConductivityTable table =
        flags.conductivity.empty() ? fem::ConductivityTable{} : io::read_conductivity_table(flags.conductivity);
    const auto montage_rows =
        flags.montage.empty() ? std::vector<io::ElectrodeRow>{} : io::read_electrodes(flags.montage);
    const auto sensors =
        flags.sensors_path.empty() ? std::vector<io::SensorRow>{} : io::read_sensors(flags.sensors_path);
    clock.lap("inputs");
    const TetMesh mesh = io::read_tet_mesh(flags.input);
    clock.lap("read");
    check_memory(context, flags.input, mesh);
    const fem::Conductivities sigma = resolve_from_file(mesh, table, flags.conductivity);
    fem::PotentialReport report;
    const std::vector<double> phi = potential(flags, mesh, sigma, montage_rows, context, clock, report);
    const fem::SolutionAnalysis analysis =
        fem::analyse_solution(mesh, sigma, phi, {.error_indicator = flags.error_indicator});
    clock.lap("statistics"); // restarts the clock; the parts' own times follow
    clock.set("fields", analysis.fields_time);
    if (flags.error_indicator) clock.set("error_indicator", analysis.error_indicator_time);
    clock.set("statistics", analysis.statistics_time);
    write_solution(flags, mesh, phi, analysis);
    if (!flags.sensor_output.empty()) write_text_atomically(flags.sensor_output, sensor_csv(mesh, sensors, phi));
    clock.lap("write");
    context.log(concat(mesh.vertex_count(), " nodes, ", mesh.tet_count(), " tets: ", report.solver.preconditioner,
                       "-CG ", report.solver.iterations, " iterations, relative residual ",
                       report.solver.relative_residual));
    summarize(mesh, report, analysis, sensors.size(), flags.error_indicator, clock, context.summary);
}

constexpr const char* description =
    "Solves div(sigma grad phi) = div(j_primary) on a labelled tet mesh with linear finite elements: current "
    "dipoles (St. Venant, subtraction or partial integration), scalp electrodes injecting currents, insulated outer "
    "boundary, zero-mean "
    "potential. Units: mm for positions, A*m for dipole moments, A for currents, S/m for conductivities, V for "
    "potentials. Tissues missing from the conductivity file take documented head defaults by name.";

constexpr const char* files_and_examples =
    "Files: --conductivity is JSON {\"scalp\": 0.43, \"3\": 1.79, \"white\": [9 numbers or 3 rows of 3]} (S/m; names "
    "or labels, each tissue once; at most 1 MiB). --sensors is CSV with the header x,y,z (mm) and --electrodes CSV "
    "with "
    "x,y,z,radius_mm,current_a (mm, mm, A), both optionally with a name column, columns in any order, '#' lines "
    "comments; at most 100 000 sensors and 10 000 electrodes. --electrodes and --electrode add up; with no fixed "
    "potential the currents must sum to zero. Before the solve, a mesh that would need more than --max-memory "
    "(about 3 kB per node) is refused.\n"
    "Examples:\n  tm-solve -i head.msh -o eeg.vtu --conductivity cond.json --dipole 0,10,40,0,0,1e-8 \\\n"
    "      --sensors electrodes.csv --sensor-potentials eeg.csv\n"
    "  tm-solve -i head.msh -o tdcs.vtu --electrode 0,90,30,10,1e-3 --electrode 0,-90,30,10,-1e-3\n"
    "  tm-solve -i head.msh -o tdcs.vtu --electrodes montage.csv      # 2 mA from C3 to Fp2; montage.csv:\n"
    "      name,x,y,z,radius_mm,current_a\n"
    "      C3,-52.1,-18.9,96.4,12.5,+0.002\n"
    "      Fp2,27.3,88.1,29.0,12.5,-0.002";

} // namespace

int main(int argc, char** argv)
{
    SolveFlags flags;
    return tools::run_tool(
        argc, argv, {"tm-solve", description, files_and_examples}, [&](CLI::App& app) { flags.add_to(app); },
        [&](tools::ToolContext& context) { run(flags, context); });
}

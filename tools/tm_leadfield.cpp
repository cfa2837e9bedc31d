// tm-leadfield: EEG and MEG lead fields by reciprocity (a transfer matrix: one solve per sensor, the AMG
// hierarchy set up once), and the tDCS lead field (one solve per electrode against a reference).
#include <cmath>

#include "core/error.h"
#include "fem/lead_field.h"
#include "fem/source_grid.h"
#include "fem/tdcs_lead_field.h"
#include "io/read_conductivity_table.h"
#include "io/read_electrodes.h"
#include "io/read_meg_sensors.h"
#include "io/read_sensors.h"
#include "io/read_sources.h"
#include "io/tet_mesh_io.h"
#include "tools/dipole_model.h"
#include "tools/lead_field_files.h"
#include "tools/run_tool.h"
#include "tools/tissue_arguments.h"

using namespace tissuemesh;

namespace {

std::string named(const std::string& name, const std::string& file, std::size_t line, const std::string& what,
                  std::size_t index)
{
    return concat(name.empty() ? concat(what, " ", index + 1) : name, " (", file, " line ", line, ")");
}

nlohmann::json mm(const Vec3& v) { return {v[0], v[1], v[2]}; }

/// The sources of the run: rows of --sources, or the grid of --source-grid-mm.
std::vector<fem::LeadFieldSource> load_sources(const std::string& path, double grid_mm, double min_distance_mm,
                                               const TetMesh& mesh, const std::vector<Label>& tissues)
{
    std::vector<fem::LeadFieldSource> sources;
    if (!path.empty()) {
        const std::vector<io::SourceRow> rows = io::read_sources(path);
        for (std::size_t k = 0; k < rows.size(); ++k)
            sources.push_back(
                {rows[k].position_mm, rows[k].orientation, named(rows[k].name, path, rows[k].line, "source", k)});
        return sources;
    }
    for (const Vec3& point :
         fem::source_grid(mesh, {.spacing_mm = grid_mm, .tissues = tissues, .min_distance_mm = min_distance_mm}))
        sources.push_back({point, std::nullopt, ""});
    if (sources.empty())
        throw InputError(concat("--source-grid-mm ", grid_mm, ": no grid point lies in the source tissues at ",
                                min_distance_mm,
                                " mm from their boundary; choose a finer grid or a smaller --source-min-distance-mm"));
    return sources;
}

/// The sidecar of an EEG or MEG lead field.
nlohmann::json lead_field_sidecar(const std::string& kind, const nlohmann::json& common, const nlohmann::json& sensors,
                                  const std::vector<fem::LeadFieldSource>& sources, const fem::LeadFieldReport& report)
{
    nlohmann::json sidecar = common;
    sidecar["kind"] = kind;
    sidecar["units"] = kind == "eeg" ? "V per A*m" : "T per A*m";
    sidecar["sensors"] = sensors;
    nlohmann::json listed = nlohmann::json::array();
    std::size_t column = 0;
    for (std::size_t s = 0; s < sources.size(); ++s) {
        nlohmann::json source{{"position_mm", mm(sources[s].position_mm)},
                              {"first_column", column},
                              {"tissue", report.source_tissues[s]}};
        source["orientation"] = sources[s].orientation ? mm(*sources[s].orientation) : nlohmann::json(nullptr);
        if (!sources[s].name.empty()) source["name"] = sources[s].name;
        column += sources[s].orientation ? 1 : 3;
        listed.push_back(source);
    }
    sidecar["sources"] = listed;
    sidecar["columns"] = "one per oriented source (its orientation), three per free source (x, y, z), in source order";
    return sidecar;
}

// Memory of a lead field, the mesh it read included: 1.34 kB per node in the program and 0.7 kB in its two MPI
// workers on bench/leadfield's 1.04 M-node mesh (spheres4 2 mm: 6.0 tets per node); 2.5 kB per node leaves room
// for meshes with more tets per node. Subtraction keeps every solve's solution (8 B per node each), the tDCS lead
// field every electrode's potentials.
constexpr double bytes_per_node = 2500;

/// Refuses a run that would need more memory than --max-memory allows, before the assembly.
void check_memory(const tools::ToolContext& context, const std::string& input, const TetMesh& mesh, double rows_kept)
{
    const double nodes = static_cast<double>(mesh.vertex_count());
    tools::require_memory(
        context.memory, input, nodes * (bytes_per_node + 8 * rows_kept),
        concat(tools::format_count(nodes), " nodes x ", tools::format_bytes(bytes_per_node + 8 * rows_kept)),
        "mesh it coarser (tm-tetra --max-volume), or use fewer electrodes");
}

/// Writes a row-major matrix and its sidecar.
void write_matrix(const std::string& path, const fem::LeadFields::Matrix& matrix, const nlohmann::json& sidecar)
{
    tools::write_lead_field(path, static_cast<std::size_t>(matrix.rows()), static_cast<std::size_t>(matrix.cols()),
                            matrix.data(), sidecar);
}

} // namespace

int main(int argc, char** argv)
{
    std::string input, conductivity, sensors_path, sources_path, output, meg_path, meg_output, tdcs_path, tdcs_output;
    std::string dipole_model = "venant", reference = "average", tdcs_reference, source_tissues, solver = "amg";
    double grid_mm = 0, min_distance_mm = 0, tolerance = 1e-6;
    fem::LeadFieldOptions options;
    int processes = 0;
    return tools::run_tool(
        argc, argv,
        {"tm-leadfield",
         "Lead fields by reciprocity on a labelled tet mesh (P1 FEM): the EEG lead field (V per A*m; one solve per "
         "electrode but one, the AMG hierarchy set up once, then every source costs a product), the MEG lead field "
         "(T per A*m: primary current and the volume currents of the FE solution; one solve per sensor), and the tDCS "
         "lead field (V per A at every node for 1 A from each electrode into a reference; tm-solve --leadfield sums "
         "any montage from it). Outputs: NumPy .npy (float64, a row per sensor, columns x, y, z per free source or one "
         "per oriented source) and a JSON sidecar of the same name (.json) with the sensors, sources, reference, "
         "units, dipole model, mesh and conductivities. Electrodes are projected onto the nearest surface triangle "
         "and interpolated on it.",
         "Files: --sensors x,y,z[,name] (mm, as tm-solve reads it); --sources x,y,z[,nx,ny,nz][,name] (mm; with "
         "nx,ny,nz one column per source); --meg-sensors x,y,z,nx,ny,nz[,x2,y2,z2][,name] (mm, unit normal; x2,y2,z2: "
         "a gradiometer's second coil, blank for magnetometers); --tdcs-electrodes "
         "x,y,z,radius_mm[,current_a][,name].\n"
         "Examples:\n  tm-leadfield -i head.msh --conductivity cond.json --sensors eeg.csv --sources src.csv -o "
         "eeg.npy\n"
         "  tm-leadfield -i head.msh --sensors eeg.csv --source-grid-mm 5 --source-tissues grey "
         "--source-min-distance-mm 2 \\\n"
         "      -o eeg.npy --meg-sensors meg.csv --meg-output meg.npy\n"
         "  tm-leadfield -i head.msh --tdcs-electrodes cap.csv --tdcs-reference Cz --tdcs-output tdcs.npy\n"
         "  tm-solve -i head.msh -o montage.vtu --leadfield tdcs.npy --electrodes montage.csv"},
        [&](CLI::App& app) {
            app.add_option("-i,--input", input, "Tet mesh, mm")->required()->check(CLI::ExistingFile);
            app.add_option("--conductivity", conductivity, "JSON {tissue name or label: S/m or 3x3 tensor}");
            app.add_option("--sensors", sensors_path, "EEG electrodes: CSV x,y,z[,name] (mm)")->type_name("FILE");
            app.add_option("-o,--output", output, "EEG lead field .npy (with a .json sidecar)")->type_name("FILE");
            app.add_option("--sources", sources_path, "Sources: CSV x,y,z[,nx,ny,nz][,name] (mm)")->type_name("FILE");
            app.add_option("--source-grid-mm", grid_mm, "Sources on a grid of this step (mm) in --source-tissues")
                ->check(CLI::PositiveNumber)
                ->excludes("--sources");
            app.add_option("--source-tissues", source_tissues,
                           "Tissues (names or labels, comma-separated) the sources "
                           "must lie in; for the grid, where it is laid");
            app.add_option("--source-min-distance-mm", min_distance_mm,
                           "Grid points at least this far from other tissues")
                ->check(CLI::NonNegativeNumber);
            app.add_option("--meg-sensors", meg_path, "MEG sensors: CSV x,y,z,nx,ny,nz[,x2,y2,z2][,name]")
                ->type_name("FILE");
            app.add_option("--meg-output", meg_output, "MEG lead field .npy (with a .json sidecar)")->type_name("FILE");
            app.add_option("--tdcs-electrodes", tdcs_path, "tDCS electrodes: CSV x,y,z,radius_mm[,current_a][,name]")
                ->type_name("FILE");
            app.add_option("--tdcs-reference", tdcs_reference,
                           "Name of the tDCS reference electrode (default: the first)");
            app.add_option("--tdcs-output", tdcs_output,
                           "tDCS lead field .npy: V per A, a row per electrode but the reference")
                ->type_name("FILE");
            app.add_option("--dipole-model", dipole_model,
                           "venant (default: the most accurate on our meshes), subtraction "
                           "(a pass over the mesh per column) or partial-integration")
                ->check(CLI::IsMember(tools::dipole_model_names));
            app.add_option("--reference", reference, "EEG reference: average, or an electrode's name")
                ->capture_default_str();
            app.add_option("--max-electrode-distance-mm", options.max_electrode_distance_mm,
                           "Electrodes farther from the surface are refused")
                ->capture_default_str()
                ->check(CLI::NonNegativeNumber);
            app.add_option("--min-meg-distance-mm", options.min_meg_distance_mm,
                           "MEG coils nearer the surface are refused")
                ->capture_default_str()
                ->check(CLI::NonNegativeNumber);
            app.add_option("--tolerance", tolerance,
                           "Relative residual of every solve (1e-6 keeps the lead field within "
                           "4e-5 of its converged value, docs/fem.md)")
                ->capture_default_str()
                ->check(CLI::PositiveNumber);
            app.add_option("--solver", solver, "Preconditioner of CG: amg or jacobi")
                ->check(CLI::IsMember({"amg", "jacobi"}));
            app.add_option("--processes", processes, "MPI processes for the AMG-CG: 0 = one per core, 1 = none")
                ->check(CLI::Range(0, 1024));
        },
        [&](tools::ToolContext& context) {
            if (sensors_path.empty() != output.empty())
                throw InputError("--sensors and -o go together; give both or neither");
            if (meg_path.empty() != meg_output.empty())
                throw InputError("--meg-sensors and --meg-output go together; give both or neither");
            if (tdcs_path.empty() != tdcs_output.empty())
                throw InputError("--tdcs-electrodes and --tdcs-output go together; give both or neither");
            if (output.empty() && meg_output.empty() && tdcs_output.empty())
                throw InputError("nothing to compute: give --sensors and -o (EEG), --meg-sensors and --meg-output, or "
                                 "--tdcs-electrodes and --tdcs-output");
            const bool eeg_or_meg = !output.empty() || !meg_output.empty();
            if (eeg_or_meg && sources_path.empty() && grid_mm == 0)
                throw InputError(
                    "the EEG and MEG lead fields need sources: give --sources FILE or --source-grid-mm STEP");
            if (grid_mm > 0 && source_tissues.empty())
                throw InputError(
                    "--source-grid-mm needs --source-tissues (e.g. grey): the tissues the grid is laid in");
            const fem::ConductivityTable table =
                conductivity.empty() ? fem::ConductivityTable{} : io::read_conductivity_table(conductivity);
            const std::vector<io::SensorRow> eeg_rows =
                sensors_path.empty() ? std::vector<io::SensorRow>{} : io::read_sensors(sensors_path);
            const std::vector<io::MegSensorRow> meg_rows =
                meg_path.empty() ? std::vector<io::MegSensorRow>{} : io::read_meg_sensors(meg_path);
            const std::vector<io::ElectrodeRow> tdcs_rows =
                tdcs_path.empty() ? std::vector<io::ElectrodeRow>{} : io::read_electrode_patches(tdcs_path);
            const TetMesh mesh = io::read_tet_mesh(input);
            const bool subtraction_rows = dipole_model == "subtraction" && eeg_or_meg;
            check_memory(
                context, input, mesh,
                static_cast<double>((subtraction_rows ? eeg_rows.size() + meg_rows.size() : 0) + tdcs_rows.size()));
            const fem::Conductivities sigma =
                conductivity.empty()
                    ? fem::resolve_conductivities(mesh, {})
                    : tools::with_source(conductivity, [&] { return fem::resolve_conductivities(mesh, table); });
            options.solver = {.preconditioner =
                                  solver == "amg" ? fem::Preconditioner::amg : fem::Preconditioner::jacobi,
                              .relative_tolerance = tolerance,
                              .processes = processes};
            options.dipole_model = tools::dipole_model_named(dipole_model);
            if (!source_tissues.empty())
                options.source_tissues =
                    tools::parse_tissue_list(source_tissues, tools::tissue_table(mesh, input), "--source-tissues");
            context.summary.update({{"nodes", mesh.vertex_count()}, {"tets", mesh.tet_count()}});
            const nlohmann::json common{{"tool", "tm-leadfield"},
                                        {"version", TM_VERSION},
                                        {"mesh", tools::mesh_description(input, mesh)},
                                        {"conductivities", tools::conductivity_description(mesh, sigma)}};
            if (eeg_or_meg) {
                std::vector<fem::EegElectrode> electrodes;
                for (std::size_t k = 0; k < eeg_rows.size(); ++k) {
                    electrodes.push_back({eeg_rows[k].position_mm,
                                          named(eeg_rows[k].name, sensors_path, eeg_rows[k].line, "electrode", k)});
                    if (reference != "average" && eeg_rows[k].name == reference) options.reference_electrode = k;
                }
                if (!eeg_rows.empty() && reference != "average" && !options.reference_electrode)
                    throw InputError(concat("--reference ", reference, ": no electrode of ", sensors_path,
                                            " has that name; ", "give one of its names or average"));
                std::vector<fem::MegSensor> meg;
                for (std::size_t k = 0; k < meg_rows.size(); ++k)
                    meg.push_back({meg_rows[k].position_mm, meg_rows[k].normal, meg_rows[k].second_coil_mm,
                                   named(meg_rows[k].name, meg_path, meg_rows[k].line, "MEG sensor", k)});
                const std::vector<fem::LeadFieldSource> sources =
                    load_sources(sources_path, grid_mm, min_distance_mm, mesh, options.source_tissues);
                fem::LeadFieldReport report;
                const fem::LeadFields fields =
                    fem::compute_lead_fields(mesh, sigma, electrodes, meg, sources, options, context.progress, &report);
                nlohmann::json solve_common = common;
                solve_common["dipole_model"] = dipole_model;
                solve_common["solver"] = {{"tolerance", tolerance},
                                          {"iterations_max", report.solver.max_iterations},
                                          {"relative_residual_max", report.solver.max_relative_residual}};
                if (!output.empty()) {
                    nlohmann::json sensors = nlohmann::json::array();
                    for (std::size_t k = 0; k < eeg_rows.size(); ++k)
                        sensors.push_back({{"name", eeg_rows[k].name.empty() ? concat("E", k + 1) : eeg_rows[k].name},
                                           {"position_mm", mm(eeg_rows[k].position_mm)},
                                           {"projected_mm", mm(report.electrodes[k].position_mm)},
                                           {"distance_mm", report.electrodes[k].distance_mm}});
                    nlohmann::json sidecar = lead_field_sidecar("eeg", solve_common, sensors, sources, report);
                    sidecar["reference"] = reference;
                    write_matrix(output, fields.eeg, sidecar);
                }
                if (!meg_output.empty()) {
                    nlohmann::json sensors = nlohmann::json::array();
                    for (std::size_t k = 0; k < meg_rows.size(); ++k) {
                        nlohmann::json sensor{
                            {"name", meg_rows[k].name.empty() ? concat("M", k + 1) : meg_rows[k].name},
                            {"position_mm", mm(meg_rows[k].position_mm)},
                            {"normal", mm(meg_rows[k].normal)}};
                        if (meg_rows[k].second_coil_mm) sensor["second_coil_mm"] = mm(*meg_rows[k].second_coil_mm);
                        sensors.push_back(sensor);
                    }
                    write_matrix(meg_output, fields.meg,
                                 lead_field_sidecar("meg", solve_common, sensors, sources, report));
                }
                context.summary.update({{"sources", sources.size()},
                                        {"columns", report.columns},
                                        {"solves", report.solves},
                                        {"unknowns", report.unknowns},
                                        {"load_nodes", report.load_nodes},
                                        {"iterations_min", report.solver.min_iterations},
                                        {"iterations_max", report.solver.max_iterations},
                                        {"iterations_mean", report.solver.mean_iterations},
                                        {"relative_residual_max", report.solver.max_relative_residual},
                                        {"processes", report.solver.processes},
                                        {"phase_seconds",
                                         {{"assembly", report.assembly_seconds},
                                          {"sources", report.sources_seconds},
                                          {"sensors", report.sensors_seconds},
                                          {"solver_prepare", report.solver.prepare_seconds},
                                          {"solver_copy", report.solver.copy_seconds},
                                          {"solver_setup", report.solver.setup_seconds},
                                          {"first_solve", report.solver.first_solve_seconds},
                                          {"later_solve_mean", report.solver.later_solve_seconds},
                                          {"solves_total", report.solver.seconds},
                                          {"products", report.products_seconds}}}});
                context.log(concat(sources.size(), " sources (", report.columns, " columns) x ", electrodes.size(),
                                   " electrodes, ", meg.size(), " MEG sensors: ", report.solves, " solves of ",
                                   report.unknowns, " unknowns, ", std::round(report.solver.mean_iterations * 10) / 10,
                                   " iterations each, ", std::round(report.solver.later_solve_seconds * 100) / 100,
                                   " s per solve after the first"));
            }
            if (!tdcs_output.empty()) {
                std::vector<fem::Electrode> patches;
                std::size_t reference_index = 0;
                bool found = tdcs_reference.empty();
                for (std::size_t k = 0; k < tdcs_rows.size(); ++k) {
                    patches.push_back({.centre_mm = tdcs_rows[k].centre_mm,
                                       .radius_mm = tdcs_rows[k].radius_mm,
                                       .name = named(tdcs_rows[k].name, tdcs_path, tdcs_rows[k].line, "electrode", k)});
                    if (!tdcs_reference.empty() && tdcs_rows[k].name == tdcs_reference)
                        reference_index = k, found = true;
                }
                if (!found)
                    throw InputError(
                        concat("--tdcs-reference ", tdcs_reference, ": no electrode of ", tdcs_path, " has that name"));
                if (tdcs_rows.front().name.empty())
                    throw InputError(concat(tdcs_path,
                                            ": the electrodes have no names; add a name column (tm-solve matches a ",
                                            "montage to the lead field by name)"));
                fem::TdcsLeadFieldReport report;
                const fem::TdcsLeadField lead_field = fem::compute_tdcs_lead_field(
                    mesh, sigma, patches, reference_index, options.solver, context.progress, &report);
                nlohmann::json sidecar = common;
                sidecar["kind"] = "tdcs";
                sidecar["units"] = "V per A";
                sidecar["rows"] =
                    "one per electrode but the reference, in file order: +1 A into it, -1 A out of the reference";
                sidecar["columns"] = "mesh nodes, zero mean";
                sidecar["reference"] = tdcs_rows[reference_index].name;
                sidecar["reference_index"] = reference_index;
                nlohmann::json electrodes = nlohmann::json::array();
                for (std::size_t k = 0; k < tdcs_rows.size(); ++k)
                    electrodes.push_back({{"name", tdcs_rows[k].name},
                                          {"centre_mm", mm(tdcs_rows[k].centre_mm)},
                                          {"radius_mm", tdcs_rows[k].radius_mm},
                                          {"area_mm2", report.electrode_area_mm2[k]},
                                          {"nodes", report.electrode_nodes[k]}});
                sidecar["electrodes"] = electrodes;
                write_matrix(tdcs_output, lead_field.potentials_v_per_a, sidecar);
                context.summary["tdcs"] = {{"electrodes", tdcs_rows.size()},
                                           {"solves", lead_field.electrodes.size()},
                                           {"iterations_max", report.solver.max_iterations},
                                           {"first_solve_seconds", report.solver.first_solve_seconds},
                                           {"later_solve_seconds", report.solver.later_solve_seconds}};
            }
        });
}

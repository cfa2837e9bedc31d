// tm-bench-leadfield: accuracy of tm-leadfield's lead fields on any mesh of the 4-shell sphere head (phantom
// spheres4: brain, CSF, skull, scalp to radii 78/80/86/92 mm, 0.33/1.79/0.01/0.43 S/m, centred at the origin).
// Each EEG column against the 4-shell series at the electrodes' projections (pushed radially onto the exact
// scalp sphere), average referenced: RDM (0..2) and MAG; each MEG column against Sarvas' formula at the
// sensors (gradiometers as the difference of their coils): RDM. Medians, 95th percentiles and maxima, and the
// same per eccentricity band.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bench/measure/spheres4_head.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "fem/sarvas_field.h"
#include "fem/sphere_series.h"
#include "io/npy.h"
#include "tools/run_tool.h"

using namespace tissuemesh;

namespace {

Vec3 vec(const nlohmann::json& values)
{
    return {values[0].get<double>(), values[1].get<double>(), values[2].get<double>()};
}

struct LeadFieldFile {
    io::NpyMatrix matrix;
    nlohmann::json sidecar;
};

LeadFieldFile read(const std::string& npy)
{
    std::string json = npy;
    json.replace(json.size() - 4, 4, ".json");
    return {io::read_npy(npy), nlohmann::json::parse(read_file_bytes(json))};
}

// The unit moments of each column and the position and eccentricity of its source.
struct Column {
    Vec3 position_mm, moment;
    double eccentricity;
};

std::vector<Column> columns_of(const nlohmann::json& sidecar)
{
    std::vector<Column> columns;
    for (const nlohmann::json& source : sidecar["sources"]) {
        const Vec3 position = vec(source["position_mm"]);
        const double eccentricity = norm(position) / bench::spheres4_series.radii_mm[0];
        if (!source["orientation"].is_null()) {
            columns.push_back({position, vec(source["orientation"]), eccentricity});
            continue;
        }
        for (const Vec3& axis : {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}})
            columns.push_back({position, axis, eccentricity});
    }
    return columns;
}

double percentile(std::vector<double> values, double fraction)
{
    if (values.empty()) return std::nan("");
    std::sort(values.begin(), values.end());
    return values[std::min(values.size() - 1, static_cast<std::size_t>(fraction * static_cast<double>(values.size())))];
}

// Median, 95th percentile and maximum of `values`, overall and in eccentricity bands.
nlohmann::json statistics(const std::vector<double>& values, const std::vector<Column>& columns)
{
    const auto summary = [](const std::vector<double>& v) {
        return nlohmann::json{{"count", v.size()},
                              {"median", percentile(v, 0.5)},
                              {"p95", percentile(v, 0.95)},
                              {"max", v.empty() ? std::nan("") : *std::max_element(v.begin(), v.end())}};
    };
    nlohmann::json result = summary(values);
    const double bands[] = {0, 0.5, 0.8, 0.9, 1.0};
    for (int b = 0; b < 4; ++b) {
        std::vector<double> in;
        for (std::size_t c = 0; c < values.size(); ++c)
            if (columns[c].eccentricity >= bands[b] && columns[c].eccentricity < bands[b + 1]) in.push_back(values[c]);
        result["eccentricity_" + concat(bands[b], "_", bands[b + 1])] = summary(in);
    }
    return result;
}

nlohmann::json measure_eeg(const std::string& path, tools::ToolContext& context)
{
    const LeadFieldFile file = read(path);
    std::vector<Vec3> on_sphere;
    for (const nlohmann::json& sensor : file.sidecar["sensors"]) {
        const Vec3 projected = vec(sensor["projected_mm"]);
        on_sphere.push_back((bench::spheres4_series.radii_mm.back() / norm(projected)) * projected);
    }
    const std::vector<Column> columns = columns_of(file.sidecar);
    if (file.matrix.rows != on_sphere.size() || file.matrix.columns != columns.size())
        throw InputError(concat(path, ": ", file.matrix.rows, " x ", file.matrix.columns, " but the sidecar has ",
                                on_sphere.size(), " sensors and ", columns.size(), " columns"));
    std::vector<double> rdm(columns.size()), mag(columns.size());
#pragma omp parallel for schedule(dynamic)
    for (std::size_t c = 0; c < columns.size(); ++c) {
        std::vector<double> numeric(on_sphere.size());
        for (std::size_t r = 0; r < on_sphere.size(); ++r) numeric[r] = file.matrix.values[r * columns.size() + c];
        const fem::Agreement a = fem::compare_potentials(
            numeric, fem::sphere_surface_potentials(bench::spheres4_series, columns[c].position_mm, columns[c].moment,
                                                    on_sphere));
        rdm[c] = a.rdm;
        mag[c] = std::abs(a.mag - 1);
    }
    const nlohmann::json rdm_statistics = statistics(rdm, columns), mag_statistics = statistics(mag, columns);
    context.log(concat("EEG ", path, ": ", on_sphere.size(), " electrodes, ", columns.size(), " columns: RDM median ",
                       rdm_statistics["median"].get<double>(), ", 95th percentile ",
                       rdm_statistics["p95"].get<double>(), ", max ", rdm_statistics["max"].get<double>(),
                       "; |MAG - 1| median ", mag_statistics["median"].get<double>()));
    return {{"electrodes", on_sphere.size()},
            {"columns", columns.size()},
            {"rdm", rdm_statistics},
            {"mag_error", mag_statistics}};
}

nlohmann::json measure_meg(const std::string& path, tools::ToolContext& context)
{
    const LeadFieldFile file = read(path);
    const nlohmann::json& sensors = file.sidecar["sensors"];
    const std::vector<Column> columns = columns_of(file.sidecar);
    if (file.matrix.rows != sensors.size() || file.matrix.columns != columns.size())
        throw InputError(concat(path, ": ", file.matrix.rows, " x ", file.matrix.columns, " but the sidecar has ",
                                sensors.size(), " sensors and ", columns.size(), " columns"));
    std::vector<double> rdm(columns.size());
#pragma omp parallel for schedule(dynamic)
    for (std::size_t c = 0; c < columns.size(); ++c) {
        double numeric_norm = 0, exact_norm = 0, cross = 0;
        for (std::size_t r = 0; r < sensors.size(); ++r) {
            const Vec3 normal = vec(sensors[r]["normal"]);
            double exact = dot(
                fem::sarvas_field(vec(sensors[r]["position_mm"]), columns[c].position_mm, columns[c].moment), normal);
            if (sensors[r].contains("second_coil_mm"))
                exact -=
                    dot(fem::sarvas_field(vec(sensors[r]["second_coil_mm"]), columns[c].position_mm, columns[c].moment),
                        normal);
            const double numeric = file.matrix.values[r * columns.size() + c];
            numeric_norm += numeric * numeric, exact_norm += exact * exact, cross += numeric * exact;
        }
        // |a / |a| - b / |b|| = sqrt(2 - 2 cos)
        rdm[c] = std::sqrt(std::max(0.0, 2 - 2 * cross / std::sqrt(numeric_norm * exact_norm)));
    }
    const nlohmann::json rdm_statistics = statistics(rdm, columns);
    context.log(concat("MEG ", path, ": ", sensors.size(), " sensors, ", columns.size(), " columns: RDM median ",
                       rdm_statistics["median"].get<double>(), ", 95th percentile ",
                       rdm_statistics["p95"].get<double>(), ", max ", rdm_statistics["max"].get<double>()));
    return {{"sensors", sensors.size()}, {"columns", columns.size()}, {"rdm", rdm_statistics}};
}

} // namespace

int main(int argc, char** argv)
{
    std::string eeg, meg;
    return tools::run_tool(
        argc, argv,
        {"tm-bench-leadfield",
         "Accuracy of tm-leadfield's lead fields on a mesh of the 4-shell sphere head (tm-phantom spheres4, centred at "
         "the origin): EEG columns against the 4-shell series (RDM, MAG; average reference), MEG columns against "
         "Sarvas' "
         "formula (RDM). Medians, 95th percentiles and maxima, overall and per eccentricity band, in --json.",
         "Example:\n  tm-bench-leadfield --eeg eeg.npy --meg meg.npy --json accuracy.json"},
        [&](CLI::App& app) {
            app.add_option("--eeg", eeg, "EEG lead field .npy of tm-leadfield (sidecar next to it)")
                ->check(CLI::ExistingFile);
            app.add_option("--meg", meg, "MEG lead field .npy of tm-leadfield (sidecar next to it)")
                ->check(CLI::ExistingFile);
        },
        [&](tools::ToolContext& context) {
            if (eeg.empty() && meg.empty()) throw InputError("give --eeg, --meg or both");
            if (!eeg.empty()) context.summary["eeg"] = measure_eeg(eeg, context);
            if (!meg.empty()) context.summary["meg"] = measure_meg(meg, context);
        });
}

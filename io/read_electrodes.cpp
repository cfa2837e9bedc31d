#include "io/read_electrodes.h"

#include <cmath>

#include "core/error.h"
#include "io/detail/csv_table.h"

namespace tissuemesh::io {

namespace {

std::vector<ElectrodeRow> read_rows(const std::filesystem::path& path, bool current_required)
{
    detail::CsvSpec spec{.rows_are = "electrode",
                         .numbers = {"x", "y", "z", "radius_mm", "current_a"},
                         .units = "mm, mm, A",
                         .max_rows = max_electrodes};
    if (!current_required) {
        spec.numbers.pop_back();
        spec.optional_numbers = {"current_a"};
    }
    std::vector<ElectrodeRow> electrodes;
    for (detail::CsvRow& row : detail::read_csv_table(path, spec)) {
        const double radius = row.numbers[3];
        if (!(radius > 0))
            throw InputError(concat(path.string(), " line ", row.line, ": radius_mm is ", radius,
                                    "; a patch radius is a positive length in mm (e.g. 12.5 for a 25 mm disc)"));
        const double current = std::isnan(row.numbers[4]) ? 0.0 : row.numbers[4];
        electrodes.push_back(
            {{row.numbers[0], row.numbers[1], row.numbers[2]}, radius, current, std::move(row.text), row.line});
    }
    return electrodes;
}

} // namespace

std::vector<ElectrodeRow> read_electrodes(const std::filesystem::path& path) { return read_rows(path, true); }

std::vector<ElectrodeRow> read_electrode_patches(const std::filesystem::path& path) { return read_rows(path, false); }

} // namespace tissuemesh::io

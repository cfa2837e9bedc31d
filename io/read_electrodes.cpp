#include "io/read_electrodes.h"

#include "core/error.h"
#include "io/detail/csv_table.h"

namespace tissuemesh::io {

std::vector<ElectrodeRow> read_electrodes(const std::filesystem::path& path)
{
    const detail::CsvSpec spec{.rows_are = "electrode",
                               .numbers = {"x", "y", "z", "radius_mm", "current_a"},
                               .units = "mm, mm, A",
                               .max_rows = max_electrodes};
    std::vector<ElectrodeRow> electrodes;
    for (detail::CsvRow& row : detail::read_csv_table(path, spec)) {
        const double radius = row.numbers[3];
        if (!(radius > 0))
            throw InputError(concat(path.string(), " line ", row.line, ": radius_mm is ", radius,
                                 "; a patch radius is a positive length in mm (e.g. 12.5 for a 25 mm disc)"));
        electrodes.push_back({{row.numbers[0], row.numbers[1], row.numbers[2]}, radius, row.numbers[4], std::move(row.text), row.line});
    }
    return electrodes;
}

} // namespace tissuemesh::io

#include "io/read_sensors.h"

#include "io/detail/csv_table.h"

namespace tissuemesh::io {

std::vector<SensorRow> read_sensors(const std::filesystem::path& path)
{
    const detail::CsvSpec spec{
        .rows_are = "sensor", .numbers = {"x", "y", "z"}, .units = "mm", .max_rows = max_sensors};
    std::vector<SensorRow> sensors;
    for (detail::CsvRow& row : detail::read_csv_table(path, spec))
        sensors.push_back({{row.numbers[0], row.numbers[1], row.numbers[2]}, std::move(row.text), row.line});
    return sensors;
}

} // namespace tissuemesh::io

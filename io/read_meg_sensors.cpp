#include "io/read_meg_sensors.h"

#include <cmath>

#include "core/error.h"
#include "io/detail/csv_table.h"

namespace tissuemesh::io {

std::vector<MegSensorRow> read_meg_sensors(const std::filesystem::path& path)
{
    const detail::CsvSpec spec{.rows_are = "MEG sensor",
                               .numbers = {"x", "y", "z", "nx", "ny", "nz"},
                               .optional_numbers = {"x2", "y2", "z2"},
                               .units = "mm, unitless, mm",
                               .max_rows = max_meg_sensors};
    std::vector<MegSensorRow> sensors;
    for (detail::CsvRow& row : detail::read_csv_table(path, spec)) {
        const std::vector<double>& v = row.numbers;
        MegSensorRow sensor{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, std::nullopt, std::move(row.text), row.line};
        const double length = norm(sensor.normal);
        if (!(length > 0) || !std::isfinite(length))
            throw InputError(concat(path.string(), " line ", row.line, ": the normal (", v[3], ", ", v[4], ", ", v[5],
                                    ") has no direction; give the coil's unit normal nx,ny,nz"));
        sensor.normal = (1 / length) * sensor.normal;
        const int given = !std::isnan(v[6]) + !std::isnan(v[7]) + !std::isnan(v[8]);
        if (given != 0 && given != 3)
            throw IoError(concat(path.string(), " line ", row.line, ": ", given,
                                 " of the second coil's x2,y2,z2 given; ",
                                 "give all three for a gradiometer or none for a magnetometer"));
        if (given == 3) {
            sensor.second_coil_mm = Vec3{v[6], v[7], v[8]};
            if (distance(*sensor.second_coil_mm, sensor.position_mm) == 0)
                throw InputError(concat(path.string(), " line ", row.line, ": the second coil is on the first, so the ",
                                        "gradiometer measures nothing; give its own position or leave x2,y2,z2 blank"));
        }
        sensors.push_back(std::move(sensor));
    }
    return sensors;
}

} // namespace tissuemesh::io

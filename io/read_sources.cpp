#include "io/read_sources.h"

#include <cmath>

#include "core/error.h"
#include "io/detail/csv_table.h"

namespace tissuemesh::io {

std::vector<SourceRow> read_sources(const std::filesystem::path& path)
{
    const detail::CsvSpec spec{.rows_are = "source",
                               .numbers = {"x", "y", "z"},
                               .optional_numbers = {"nx", "ny", "nz"},
                               .units = "mm, unitless",
                               .max_rows = max_sources};
    std::vector<SourceRow> sources;
    for (detail::CsvRow& row : detail::read_csv_table(path, spec)) {
        SourceRow source{{row.numbers[0], row.numbers[1], row.numbers[2]}, std::nullopt, std::move(row.text), row.line};
        const int given = !std::isnan(row.numbers[3]) + !std::isnan(row.numbers[4]) + !std::isnan(row.numbers[5]);
        if (given != 0 && given != 3)
            throw IoError(
                concat(path.string(), " line ", row.line, ": ", given, " of the orientation's nx,ny,nz given; ",
                       "give all three or leave the columns out (free orientation: three columns per source)"));
        if (!sources.empty() && (given == 3) != sources.front().orientation.has_value())
            throw IoError(concat(path.string(), " line ", row.line, ": ",
                                 given == 3 ? "an orientation" : "no orientation", " where line ", sources.front().line,
                                 given == 3 ? " has none" : " has one",
                                 "; fix the orientation of every source or of none"));
        if (given == 3) {
            const Vec3 n{row.numbers[3], row.numbers[4], row.numbers[5]};
            const double length = norm(n);
            if (!(length > 0) || !std::isfinite(length))
                throw InputError(concat(path.string(), " line ", row.line, ": the orientation (", n[0], ", ", n[1],
                                        ", ", n[2], ") has no direction; give a nonzero vector nx,ny,nz"));
            source.orientation = (1 / length) * n;
        }
        sources.push_back(std::move(source));
    }
    return sources;
}

} // namespace tissuemesh::io

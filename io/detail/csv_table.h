// Comma-separated tables with a header line of column names: the sensor and electrode files of tm-solve.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace tissuemesh::io::detail {

/// What a table must look like.
struct CsvSpec {
    std::string rows_are;             ///< what a row is, for messages: "sensor", "electrode"
    std::vector<std::string> numbers; ///< required number columns, lower case ("x", "y", "z", ...)
    /// Number columns the header may leave out ("nx", "ny", "nz"); in a row a blank field reads as NaN
    /// (whether that is allowed is the caller's rule).
    std::vector<std::string> optional_numbers;
    std::string text_column = "name";  ///< an optional text column ("" none)
    std::string units;                 ///< the expected header with units, for messages: "x,y,z (mm)"
    std::size_t max_rows = 0;          ///< more rows are refused
    std::size_t max_bytes = 64u << 20; ///< larger files are refused before they are read
};

/// One data row.
struct CsvRow {
    std::size_t line = 0; ///< 1-based line in the file
    /// CsvSpec::numbers (finite), then CsvSpec::optional_numbers (finite, or NaN when the header has no
    /// such column or the field is blank)
    std::vector<double> numbers;
    std::string text; ///< the text column ("" when the table has none)
};

/// Reads a table: the first line that is neither blank nor a comment ('#') is the header; its columns
/// may come in any order, in any case, with spaces around them, and the text column may be left out.
/// Fields are trimmed; a field in double quotes loses them (no commas inside). A UTF-8 byte-order mark
/// and Windows line ends are accepted; blank lines and '#' lines are skipped everywhere. Numbers are
/// decimal (a leading '+' allowed), finite. Names must be unique and not empty.
/// @throws IoError when the file is missing, empty, larger than `max_bytes`, has no header or no rows,
///         a header column is unknown, repeated or missing, a row has the wrong number of fields, a number
///         field is not a finite number, a name is empty, repeated or holds control characters, or there
///         are more than `max_rows` rows. Messages: "<file> line <n>: <problem>; <fix>".
std::vector<CsvRow> read_csv_table(const std::filesystem::path& path, const CsvSpec& spec);

/// `text` fit for a one-line message: at most `max_chars` characters ("..." after them), control and
/// non-ASCII bytes as '?'.
std::string printable(const std::string& text, std::size_t max_chars = 40);

} // namespace tissuemesh::io::detail

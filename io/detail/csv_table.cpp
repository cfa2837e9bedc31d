#include "io/detail/csv_table.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <string_view>

#include "core/atomic_file.h"
#include "core/error.h"

namespace tissuemesh::io::detail {
namespace fs = std::filesystem;

namespace {

std::string_view trimmed(std::string_view text)
{
    const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
    while (!text.empty() && blank(text.front())) text.remove_prefix(1);
    while (!text.empty() && blank(text.back())) text.remove_suffix(1);
    return text;
}

/// The comma-separated fields of a line, trimmed, with one pair of enclosing double quotes removed.
std::vector<std::string_view> split_fields(std::string_view line)
{
    std::vector<std::string_view> fields;
    for (std::size_t start = 0;;) {
        const std::size_t comma = line.find(',', start);
        std::string_view field =
            trimmed(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
        if (field.size() >= 2 && field.front() == '"' && field.back() == '"')
            field = trimmed(field.substr(1, field.size() - 2));
        fields.push_back(field);
        if (comma == std::string_view::npos) return fields;
        start = comma + 1;
    }
}

std::string lower(std::string_view text)
{
    std::string result(text);
    for (char& c : result)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return result;
}

/// A decimal number filling the whole field, finite; a leading '+' is allowed ("+1e-3" for an anode).
bool parse_finite(std::string_view field, double& value)
{
    if (field.size() > 1 && field.front() == '+' && field[1] != '-' && field[1] != '+') field.remove_prefix(1);
    if (field.empty()) return false;
    const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
    return error == std::errc{} && end == field.data() + field.size() && std::isfinite(value);
}

/// Where each column of the header goes: the index into CsvSpec::numbers followed by optional_numbers, or -1
/// for the text column.
class Header {
public:
    Header(const std::string& file, std::size_t line, std::string_view text, const CsvSpec& spec)
    {
        const std::string expected = expected_header(spec);
        std::map<std::string, std::size_t> seen;
        for (std::string_view field : split_fields(text)) {
            const std::string name = lower(field);
            double number = 0;
            if (columns_.empty() && parse_finite(field, number))
                throw IoError(concat(file, " line ", line, ": the first line is data, not a header; put the header ",
                                     expected, " first"));
            const auto known = std::find(spec.numbers.begin(), spec.numbers.end(), name);
            int index = static_cast<int>(known - spec.numbers.begin());
            if (known == spec.numbers.end()) {
                const auto optional = std::find(spec.optional_numbers.begin(), spec.optional_numbers.end(), name);
                index = optional == spec.optional_numbers.end()
                            ? -1
                            : static_cast<int>(spec.numbers.size() +
                                               static_cast<std::size_t>(optional - spec.optional_numbers.begin()));
            }
            if (index < 0 && (spec.text_column.empty() || name != spec.text_column))
                throw IoError(concat(file, " line ", line, ": unknown column '", printable(std::string(field)), "'",
                                     hint(name), "; the header is ", expected));
            if (const auto [at, inserted] = seen.emplace(name, columns_.size() + 1); !inserted)
                throw IoError(concat(file, " line ", line, ": column '", name, "' appears twice (columns ", at->second,
                                     " and ", columns_.size() + 1, "); the header is ", expected));
            columns_.push_back(index);
        }
        for (const std::string& name : spec.numbers)
            if (!seen.count(name))
                throw IoError(
                    concat(file, " line ", line, ": the header has no column '", name, "'; the header is ", expected));
    }

    const std::vector<int>& columns() const { return columns_; }

    static std::string expected_header(const CsvSpec& spec)
    {
        std::string text;
        for (const std::string& name : spec.numbers) text += (text.empty() ? "" : ",") + name;
        std::string optional;
        for (const std::string& name : spec.optional_numbers) optional += (optional.empty() ? "" : ",") + name;
        if (!spec.text_column.empty()) optional += (optional.empty() ? "" : ", ") + spec.text_column;
        if (!optional.empty()) text += " (and optionally " + optional + ")";
        return concat(text, ", units ", spec.units);
    }

private:
    /// A likely mistake behind an unknown column: another unit than the one the name carries.
    static std::string hint(const std::string& name)
    {
        if (name.starts_with("current") && name != "current_a") return " (give the current in ampere, as current_a)";
        if (name.starts_with("radius") && name != "radius_mm") return " (give the radius in mm, as radius_mm)";
        return "";
    }

    std::vector<int> columns_;
};

/// The lines of `bytes` (a UTF-8 byte-order mark dropped; "\r\n" ends like "\n").
std::vector<std::string_view> lines_of(std::string_view bytes)
{
    if (bytes.starts_with("\xEF\xBB\xBF")) bytes.remove_prefix(3);
    std::vector<std::string_view> lines;
    for (std::size_t start = 0; start < bytes.size();) {
        const std::size_t end = std::min(bytes.find('\n', start), bytes.size());
        lines.push_back(bytes.substr(start, end - start));
        start = end + 1;
    }
    return lines;
}

bool skipped(std::string_view line)
{
    line = trimmed(line);
    return line.empty() || line.front() == '#';
}

} // namespace

std::string printable(const std::string& text, std::size_t max_chars)
{
    std::string result;
    for (const char c : text.substr(0, max_chars)) result += c >= 0x20 && c < 0x7f ? c : '?';
    return text.size() > max_chars ? result + "..." : result;
}

std::vector<CsvRow> read_csv_table(const fs::path& path, const CsvSpec& spec)
{
    require_readable_file(path);
    const std::string file = path.string();
    std::error_code error;
    const std::uintmax_t size = fs::file_size(path, error);
    if (error) throw IoError(concat(file, ": cannot read its size (", error.message(), "); check the file"));
    if (size == 0)
        throw IoError(concat(file, ": the file is empty; write the header ", Header::expected_header(spec),
                             " and one line per ", spec.rows_are));
    if (size > spec.max_bytes)
        throw IoError(concat(file, ": ", size, " bytes, more than the ", spec.max_bytes, " a file of ", spec.max_rows,
                             " ", spec.rows_are, "s may take; check that it is the right file"));
    const std::string bytes = read_file_bytes(path);
    const std::vector<std::string_view> lines = lines_of(bytes);
    std::size_t at = 0;
    while (at < lines.size() && skipped(lines[at])) ++at;
    if (at == lines.size())
        throw IoError(concat(file, ": no header line (only blank or '#' lines); write the header ",
                             Header::expected_header(spec)));
    const Header header(file, at + 1, lines[at], spec);
    const bool named = std::find(header.columns().begin(), header.columns().end(), -1) != header.columns().end();
    std::vector<CsvRow> rows;
    std::map<std::string, std::size_t> names;
    for (++at; at < lines.size(); ++at) {
        if (skipped(lines[at])) continue;
        const std::size_t line = at + 1;
        if (rows.size() == spec.max_rows)
            throw IoError(concat(file, " line ", line, ": more than ", spec.max_rows, " ", spec.rows_are,
                                 "s; split the file or check that it is the right one"));
        const std::vector<std::string_view> fields = split_fields(lines[at]);
        if (fields.size() != header.columns().size())
            throw IoError(concat(file, " line ", line, ": ", fields.size(), " fields where the header has ",
                                 header.columns().size(), " columns; give one value per column (no commas in names)"));
        CsvRow row{line, std::vector<double>(spec.numbers.size() + spec.optional_numbers.size(), std::nan("")), ""};
        for (std::size_t k = 0; k < fields.size(); ++k) {
            const int column = header.columns()[k];
            if (column < 0) {
                row.text = std::string(fields[k]);
                continue;
            }
            const auto index = static_cast<std::size_t>(column);
            const bool optional = index >= spec.numbers.size();
            if (optional && fields[k].empty()) continue;
            if (!parse_finite(fields[k], row.numbers[index]))
                throw IoError(
                    concat(file, " line ", line, ", column ",
                           optional ? spec.optional_numbers[index - spec.numbers.size()] : spec.numbers[index], ": '",
                           printable(std::string(fields[k])), "' is not a finite number; write plain decimals (",
                           Header::expected_header(spec), ")"));
        }
        if (named) {
            if (row.text.empty())
                throw IoError(concat(file, " line ", line, ": the ", spec.rows_are, " has no ", spec.text_column,
                                     "; name every ", spec.rows_are, " or leave the column out"));
            if (std::any_of(row.text.begin(), row.text.end(), [](char c) { return c >= 0 && c < 0x20; }))
                throw IoError(concat(file, " line ", line, ": the ", spec.text_column, " '", printable(row.text),
                                     "' holds control characters; use plain text"));
            if (const auto [first, inserted] = names.emplace(row.text, line); !inserted)
                throw IoError(concat(file, " line ", line, ": ", spec.text_column, " '", printable(row.text),
                                     "' is also on line ", first->second, "; give each ", spec.rows_are,
                                     " its own name"));
        }
        rows.push_back(std::move(row));
    }
    if (rows.empty())
        throw IoError(concat(file, ": no ", spec.rows_are, "s after the header; add one line per ", spec.rows_are, " (",
                             Header::expected_header(spec), ")"));
    return rows;
}

} // namespace tissuemesh::io::detail

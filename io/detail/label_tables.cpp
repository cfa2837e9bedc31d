#include "io/detail/label_tables.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "io/detail/csv_table.h"

namespace tissuemesh::io::detail {
namespace {

std::string trimmed(std::string_view text)
{
    const auto space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
    while (!text.empty() && space(text.front())) text.remove_prefix(1);
    while (!text.empty() && space(text.back())) text.remove_suffix(1);
    return std::string(text);
}

std::vector<std::string> lines_of(const std::string& text)
{
    std::vector<std::string> lines;
    std::size_t start = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0; // a UTF-8 byte-order mark
    while (start <= text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        std::string line = text.substr(start, end - start);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        lines.push_back(std::move(line));
        start = end + 1;
    }
    return lines;
}

std::vector<std::string> split(const std::string& line, char separator)
{
    std::vector<std::string> fields;
    std::stringstream in(line);
    for (std::string field; std::getline(in, field, separator);) fields.push_back(field);
    if (!line.empty() && line.back() == separator) fields.emplace_back();
    return fields;
}

std::vector<std::string> words(const std::string& text)
{
    std::istringstream in(text);
    std::vector<std::string> result;
    for (std::string word; in >> word;) result.push_back(word);
    return result;
}

bool is_number(const std::string& token)
{
    double value = 0;
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    return error == std::errc() && end == token.data() + token.size();
}

/// Collects names line by line with the checks every format shares.
class Table {
public:
    Table(const std::string& what, const char* layout) : what_(what), layout_(layout) {}

    [[noreturn]] void fail(std::size_t line, const std::string& problem) const
    {
        throw InputError(concat(what_, " line ", line, ": ", problem, "; ", layout_));
    }

    void add(std::size_t line, const std::string& label_text, const std::string& name_text)
    {
        long long label = -1;
        const auto [end, error] = std::from_chars(label_text.data(), label_text.data() + label_text.size(), label);
        if (error != std::errc() || end != label_text.data() + label_text.size() || label < 0 || label > 65535)
            fail(line, concat("\"", printable(label_text), "\" is not a label number in 0..65535"));
        const std::string name = trimmed(name_text);
        if (name.empty()) fail(line, concat("label ", label, " has an empty name"));
        if (!names_.emplace(static_cast<Label>(label), name).second)
            fail(line, concat("label ", label, " is named twice (\"", printable(names_[static_cast<Label>(label)]),
                              "\" and \"", printable(name), "\")"));
    }

    TissueNames finish() const
    {
        if (names_.empty()) throw InputError(concat(what_, ": the table names no label; ", layout_));
        return names_;
    }

private:
    const std::string& what_;
    const char* layout_;
    TissueNames names_;
};

TissueNames parse_freesurfer(const std::vector<std::string>& lines, const std::string& what)
{
    Table table(what, "a FreeSurfer colour table has lines \"<label> <name> <r> <g> <b> <a>\" (name without spaces)");
    for (std::size_t n = 0; n < lines.size(); ++n) {
        const std::vector<std::string> fields = words(lines[n].substr(0, lines[n].find('#')));
        if (fields.empty()) continue;
        if (fields.size() != 2 && fields.size() != 6) table.fail(n + 1, concat(fields.size(), " fields instead of 6"));
        if (fields.size() == 6 && !std::all_of(fields.begin() + 2, fields.end(), is_number))
            table.fail(n + 1, "the colour is not 4 numbers (a name with spaces?)");
        table.add(n + 1, fields[0], fields[1]);
    }
    return table.finish();
}

TissueNames parse_itksnap(const std::vector<std::string>& lines, const std::string& what)
{
    Table table(what,
                "an ITK-SNAP label file has lines \"<label> <r> <g> <b> <alpha> <visible> <mesh> \\\"<name>\\\"\"");
    for (std::size_t n = 0; n < lines.size(); ++n) {
        const std::string line = trimmed(lines[n]);
        if (line.empty() || line[0] == '#') continue;
        const std::size_t open = line.find('"'), close = line.rfind('"');
        if (open == std::string::npos || close == open) table.fail(n + 1, "no name in double quotes");
        const std::vector<std::string> fields = words(line.substr(0, open));
        if (fields.size() != 7 || !std::all_of(fields.begin(), fields.end(), is_number))
            table.fail(n + 1, concat(fields.size(), " numbers before the name instead of 7"));
        if (!trimmed(line.substr(close + 1)).empty()) table.fail(n + 1, "text after the quoted name");
        table.add(n + 1, fields[0], line.substr(open + 1, close - open - 1));
    }
    return table.finish();
}

std::size_t column(const std::vector<std::string>& header, const std::string& name)
{
    for (std::size_t c = 0; c < header.size(); ++c) {
        std::string field = trimmed(header[c]);
        std::transform(field.begin(), field.end(), field.begin(), [](unsigned char ch) { return std::tolower(ch); });
        if (field == name) return c;
    }
    return header.size();
}

TissueNames parse_bids(const std::vector<std::string>& lines, const std::string& what)
{
    Table table(what, "a BIDS dseg.tsv has a tab-separated header with the columns \"index\" and \"name\"");
    std::size_t n = 0;
    while (n < lines.size() && trimmed(lines[n]).empty()) ++n;
    if (n == lines.size()) table.fail(1, "the file is empty");
    const std::vector<std::string> header = split(lines[n], '\t');
    const std::size_t index = column(header, "index"), name = column(header, "name");
    if (index == header.size() || name == header.size())
        table.fail(n + 1, concat("the header \"", printable(lines[n], 60), "\" lacks \"",
                                 index == header.size() ? "index" : "name", "\""));
    for (++n; n < lines.size(); ++n) {
        if (trimmed(lines[n]).empty()) continue;
        const std::vector<std::string> fields = split(lines[n], '\t');
        if (fields.size() != header.size())
            table.fail(n + 1, concat(fields.size(), " tab-separated fields under a header of ", header.size()));
        table.add(n + 1, trimmed(fields[index]), fields[name]);
    }
    return table.finish();
}

} // namespace

LabelTableFormat detect_label_table(const std::string& text, bool tsv_name)
{
    if (tsv_name) return LabelTableFormat::bids_tsv;
    for (const std::string& line : lines_of(text)) {
        const std::string content = trimmed(line);
        if (content.empty() || content[0] == '#') continue;
        return content.find('"') != std::string::npos ? LabelTableFormat::itksnap : LabelTableFormat::freesurfer_lut;
    }
    return LabelTableFormat::freesurfer_lut;
}

TissueNames parse_label_table(const std::string& text, const std::string& what, LabelTableFormat format)
{
    const std::vector<std::string> lines = lines_of(text);
    switch (format) {
    case LabelTableFormat::freesurfer_lut: return parse_freesurfer(lines, what);
    case LabelTableFormat::itksnap: return parse_itksnap(lines, what);
    case LabelTableFormat::bids_tsv: return parse_bids(lines, what);
    }
    return {};
}

} // namespace tissuemesh::io::detail

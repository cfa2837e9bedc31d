#include "io/read_conductivity_table.h"

#include <cmath>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/detail/csv_table.h"

namespace tissuemesh::io {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* example = "{\"scalp\": 0.43, \"skull\": 0.01, \"3\": 1.79} in S/m";

/// Throws when the JSON text nests deeper than a table of 3x3 tensors (object, rows, entries): checked on the
/// bytes, before the parser builds a value per bracket.
void check_nesting(const std::string& file, std::string_view text)
{
    int depth = 0;
    std::size_t line = 1;
    bool in_string = false;
    for (std::size_t k = 0; k < text.size(); ++k) {
        const char c = text[k];
        if (c == '\n') ++line;
        if (in_string) {
            if (c == '\\') ++k;
            else if (c == '"') in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '{' || c == '[') {
            if (++depth > 3)
                throw IoError(concat(file, " line ", line, ": nested ", depth, " deep; a table is ", example,
                                     ", a tensor 9 numbers or 3 rows of 3"));
        } else if (c == '}' || c == ']') {
            --depth;
        }
    }
}

/// The tissue a key names, for finding repeats: a label number by its value ("03" is "3"), a name in lower case.
std::string normalized(const std::string& key)
{
    if (!key.empty() && key.find_first_not_of("0123456789") == std::string::npos) {
        const std::size_t first = key.find_first_not_of('0');
        return first == std::string::npos ? "0" : key.substr(first);
    }
    std::string lower = key;
    for (char& c : lower)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return "name " + lower;
}

/// The parsed document; a key given twice at the top (JSON parsers keep only the last) is an error.
json parse_table(const std::string& file, const std::string& text)
{
    std::map<std::string, std::string> seen;
    std::string repeated;
    const auto watch_keys = [&](int depth, json::parse_event_t event, json& parsed) {
        if (event == json::parse_event_t::key && depth == 1 && repeated.empty()) {
            const std::string key = parsed.get<std::string>();
            const auto [first, inserted] = seen.emplace(normalized(key), key);
            if (!inserted)
                repeated = concat("\"", detail::printable(first->second), "\" and \"", detail::printable(key), "\"");
        }
        return true;
    };
    json document;
    try {
        document = json::parse(text, watch_keys);
    } catch (const json::exception& error) {
        std::string what = error.what();
        if (const std::size_t end = what.find("] "); what.starts_with("[json.exception") && end != std::string::npos)
            what = what.substr(end + 2);
        throw IoError(concat(file, ": not valid JSON (", detail::printable(what, 160), "); write ", example));
    }
    if (!document.is_object())
        throw IoError(concat(file, ": the table is a JSON ", document.type_name(), ", not an object; write ", example));
    if (!repeated.empty())
        throw InputError(concat(file, ": ", repeated, " name the same tissue; give each tissue once"));
    if (document.empty())
        throw InputError(concat(file, ": the table is empty; give tissues as ", example,
                                ", or leave out --conductivity for the head defaults"));
    return document;
}

/// A tensor from 9 numbers or 3 rows of 3; false when `value` has another shape or a non-finite entry.
bool read_tensor(const json& value, Mat3& tensor)
{
    if (!value.is_array()) return false;
    std::size_t k = 0;
    const auto take = [&](const json& entry) {
        if (!entry.is_number() || k == 9 || !std::isfinite(entry.get<double>())) return false;
        tensor[k++] = entry.get<double>();
        return true;
    };
    if (value.size() == 9) {
        for (const json& entry : value)
            if (!take(entry)) return false;
        return true;
    }
    if (value.size() != 3) return false;
    for (const json& row : value) {
        if (!row.is_array() || row.size() != 3) return false;
        for (const json& entry : row)
            if (!take(entry)) return false;
    }
    return true;
}

} // namespace

std::map<std::string, Mat3> read_conductivity_table(const fs::path& path)
{
    require_readable_file(path);
    const std::string file = path.string();
    std::error_code error;
    const std::uintmax_t size = fs::file_size(path, error);
    if (error) throw IoError(concat(file, ": cannot read its size (", error.message(), "); check the file"));
    if (size == 0) throw IoError(concat(file, ": the file is empty; write ", example));
    if (size > max_conductivity_table_bytes)
        throw IoError(concat(file, ": ", size, " bytes is more than a conductivity table needs (at most ",
                             max_conductivity_table_bytes, "); check that it is the right file"));
    const std::string text = read_file_bytes(path);
    check_nesting(file, text);
    const json document = parse_table(file, text);
    std::map<std::string, Mat3> table;
    for (const auto& [key, value] : document.items()) {
        if (key.empty())
            throw InputError(concat(file, ": a key is empty; use a tissue name or label number, as in ", example));
        const std::string shown = concat("\"", detail::printable(key), "\"");
        if (value.is_number()) {
            const double sigma = value.get<double>();
            if (!(sigma > 0) || !std::isfinite(sigma))
                throw InputError(concat(file, ": ", shown, " is ", sigma, " S/m; conductivities are positive numbers"));
            table[key] = {sigma, 0, 0, 0, sigma, 0, 0, 0, sigma};
            continue;
        }
        Mat3 tensor{};
        if (!read_tensor(value, tensor))
            throw InputError(concat(file, ": ", shown,
                                    " is neither a number (S/m) nor a tensor of 9 finite numbers (3 rows "
                                    "of 3, S/m): found JSON ",
                                    value.type_name()));
        table[key] = tensor;
    }
    return table;
}

} // namespace tissuemesh::io

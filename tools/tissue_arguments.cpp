#include "tools/tissue_arguments.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <optional>

#include "core/error.h"

namespace tissuemesh::tools {
namespace {

constexpr unsigned long long largest_label = 65535;
/// Tissues listed in a message at most (a FreeSurfer table names over a thousand).
constexpr std::size_t listed_tissues = 30;

bool same_in_any_case(std::string_view a, std::string_view b)
{
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
           });
}

/// "1 scalp, 2 skull, 3": the tissues a message offers, those of the input when known, else the named ones.
std::string known_tissues(const TissueTable& table)
{
    std::vector<Label> labels(table.present.begin(), table.present.end());
    if (labels.empty())
        for (const auto& [label, name] : table.names) labels.push_back(label);
    if (labels.empty()) return "none named (give label numbers)";
    std::string text;
    for (std::size_t i = 0; i < labels.size() && i < listed_tissues; ++i) {
        const auto named = table.names.find(labels[i]);
        text += concat(i > 0 ? ", " : "", labels[i],
                       named != table.names.end() && !named->second.empty() ? " " + named->second : "");
    }
    if (labels.size() > listed_tissues) text += concat(" and ", labels.size() - listed_tissues, " more");
    return text;
}

std::string where(const TissueTable& table) { return table.source.empty() ? std::string("the input") : table.source; }

/// The label named `text`: the exact name, else the one name equal in any case; none when there is none.
std::optional<Label> named_label(std::string_view text, const TissueTable& table, std::string_view option)
{
    std::vector<Label> any_case;
    for (const auto& [label, name] : table.names) {
        if (name == text) return label;
        if (same_in_any_case(name, text)) any_case.push_back(label);
    }
    if (any_case.size() > 1)
        throw InputError(concat(option, ": tissue \"", text, "\" names labels ", any_case[0], " and ", any_case[1],
                                " of ", where(table), " in different cases; give the label number"));
    if (any_case.empty()) return std::nullopt;
    return any_case.front();
}

bool is_integer(std::string_view text)
{
    const std::string_view digits = text.starts_with('-') || text.starts_with('+') ? text.substr(1) : text;
    return !digits.empty() && std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; });
}

} // namespace

TissueTable tissue_table(const LabelImage& image, const std::string& source)
{
    TissueTable table{image.names(), {}, source};
    for (const auto& [label, voxels] : count_labels(image)) table.present.insert(label);
    return table;
}

TissueTable tissue_table(const InterfaceComplex& complex, const std::string& source)
{
    TissueTable table{complex.names, {}, source};
    for (const LabelPair& pair : complex.sides) table.present.insert({pair.from, pair.to});
    return table;
}

TissueTable tissue_table(const TetMesh& mesh, const std::string& source)
{
    TissueTable table{mesh.names, {mesh.tet_labels.begin(), mesh.tet_labels.end()}, source};
    return table;
}

Label parse_tissue(std::string_view text, const TissueTable& table, std::string_view option)
{
    if (const std::optional<Label> named = named_label(text, table, option)) return *named;
    if (!is_integer(text))
        throw InputError(concat(option, ": unknown tissue \"", text, "\"; the tissues of ", where(table), " are ",
                                known_tissues(table), " (names in any case, or label numbers)"));
    unsigned long long number = largest_label + 1;
    const bool negative = text.starts_with('-');
    const std::string_view digits = text.starts_with('+') || negative ? text.substr(1) : text;
    std::from_chars(digits.data(), digits.data() + digits.size(), number); // overflow leaves it out of range
    if (negative || number > largest_label)
        throw InputError(concat(option, ": tissue ", text, " is not a label number; labels are 0..", largest_label));
    const Label label = static_cast<Label>(number);
    if (!table.present.empty() && table.present.count(label) == 0)
        throw InputError(
            concat(option, ": ", where(table), " has no tissue ", label, "; its tissues are ", known_tissues(table)));
    return label;
}

std::vector<Label> parse_tissue_list(std::string_view text, const TissueTable& table, std::string_view option)
{
    std::vector<Label> labels;
    for (std::size_t start = 0;;) {
        const std::size_t comma = text.find(',', start);
        labels.push_back(parse_tissue(text.substr(start, comma - start), table, option));
        if (comma == std::string_view::npos) return labels;
        start = comma + 1;
    }
}

TissueSetting parse_tissue_setting(std::string_view item, const TissueTable& table, std::string_view option,
                                   std::string_view example)
{
    const std::size_t equals = item.find('=');
    if (equals == std::string_view::npos)
        throw InputError(concat(option, " ", item,
                                ": expected TISSUE=VALUE with TISSUE a name or a label number (e.g. ", option, " ",
                                example, ")"));
    return {parse_tissue(item.substr(0, equals), table, concat(option, " ", item)),
            std::string(item.substr(equals + 1))};
}

} // namespace tissuemesh::tools

#include "fem/conductivities.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>
#include <set>

#include "core/error.h"

namespace tissuemesh::fem {
namespace {

std::string lower(std::string text)
{
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

std::optional<Label> parse_label(const std::string& key)
{
    unsigned value = 0;
    const auto [end, error] = std::from_chars(key.data(), key.data() + key.size(), value);
    if (error != std::errc() || end != key.data() + key.size() || value > 65535) return std::nullopt;
    return static_cast<Label>(value);
}

std::string name_of(const TetMesh& mesh, Label label)
{
    const auto found = mesh.names.find(label);
    return found == mesh.names.end() ? std::to_string(label) : found->second;
}

std::string known_tissues(const TetMesh& mesh, const std::set<Label>& present)
{
    std::string list;
    for (Label label : present) list += (list.empty() ? "" : ", ") + concat(label, " (", name_of(mesh, label), ")");
    return list;
}

// Symmetric positive definite: symmetric to round-off and positive leading principal minors.
void check_tensor(const Mat3& m, const std::string& key)
{
    for (double value : m)
        if (!std::isfinite(value))
            throw InputError(concat("conductivity of '", key, "' is not finite; give S/m values"));
    const double scale = std::max({std::abs(m[0]), std::abs(m[4]), std::abs(m[8]), 1e-300});
    const bool symmetric = std::abs(m[1] - m[3]) <= 1e-12 * scale && std::abs(m[2] - m[6]) <= 1e-12 * scale &&
                           std::abs(m[5] - m[7]) <= 1e-12 * scale;
    const double minor2 = m[0] * m[4] - m[1] * m[3];
    if (!symmetric || m[0] <= 0 || minor2 <= 0 || determinant(m) <= 0)
        throw InputError(concat("conductivity of '", key, "' is not a symmetric positive definite tensor (S/m); ",
                                "give a positive scalar or an SPD 3x3 tensor"));
}

/// Whether `text` matches `pattern`, where '*' stands for any run of characters (case already folded).
bool glob_match(const std::string& pattern, const std::string& text)
{
    std::size_t p = 0, t = 0, star = std::string::npos, resume = 0;
    while (t < text.size()) {
        if (p < pattern.size() && pattern[p] == '*') {
            star = p++;
            resume = t;
        } else if (p < pattern.size() && pattern[p] == text[t]) {
            ++p, ++t;
        } else if (star != std::string::npos) {
            p = star + 1;
            t = ++resume;
        } else {
            return false;
        }
    }
    while (p < pattern.size() && pattern[p] == '*') ++p;
    return p == pattern.size();
}

/// Tissues the table's patterns ("rib_*", "*") give a value, for those no plain key named: the pattern with
/// the most characters other than '*' wins; two equally specific patterns with different values are an error.
void apply_patterns(const TetMesh& mesh, const ConductivityTable& table, const std::set<Label>& present,
                    Conductivities& result)
{
    std::map<Label, std::pair<std::string, std::size_t>> chosen; // pattern and its specificity
    for (const auto& [key, tensor] : table) {
        if (key.find('*') == std::string::npos) continue;
        check_tensor(tensor, key);
        const std::size_t specificity = key.size() - static_cast<std::size_t>(std::count(key.begin(), key.end(), '*'));
        bool used = false;
        for (const Label label : present) {
            if (result.by_label.count(label) && !chosen.count(label)) continue; // a plain key named it
            if (!glob_match(lower(key), lower(name_of(mesh, label)))) continue;
            used = true;
            const auto found = chosen.find(label);
            if (found != chosen.end() && found->second.second > specificity) continue;
            if (found != chosen.end() && found->second.second == specificity && table.at(found->second.first) != tensor)
                throw InputError(concat("conductivity table: '", found->second.first, "' and '", key,
                                        "' both match tissue ", label, " (", name_of(mesh, label),
                                        ") with different values; name it alone"));
            if (found == chosen.end() || found->second.second < specificity) {
                chosen[label] = {key, specificity};
                result.by_label[label] = tensor;
            }
        }
        if (!used)
            throw InputError(concat("conductivity table: the pattern '", key,
                                    "' matches no tissue of the mesh (tissues: ", known_tissues(mesh, present), ")"));
    }
}

} // namespace

Mat3 isotropic(double sigma) { return {sigma, 0, 0, 0, sigma, 0, 0, 0, sigma}; }

const std::map<std::string, double>& default_head_conductivities()
{
    static const std::map<std::string, double> table = {
        {"scalp", 0.43}, {"skin", 0.43}, {"skull", 0.01}, {"bone", 0.01}, {"csf", 1.79},  {"grey", 0.33},
        {"gray", 0.33},  {"gm", 0.33},   {"white", 0.14}, {"wm", 0.14},   {"brain", 0.33}};
    return table;
}

Conductivities resolve_conductivities(const TetMesh& mesh, const ConductivityTable& table, bool use_defaults)
{
    const std::set<Label> present(mesh.tet_labels.begin(), mesh.tet_labels.end());
    Conductivities result;
    std::map<Label, std::string> key_of; // a tissue named twice ("brain" and "4") would keep one value silently
    for (const auto& [key, tensor] : table) {
        if (key.find('*') != std::string::npos) continue; // patterns: below
        check_tensor(tensor, key);
        std::optional<Label> label = parse_label(key);
        if (!label)
            for (const auto& [candidate, name] : mesh.names)
                if (lower(name) == lower(key) && present.count(candidate)) label = candidate;
        if (!label || !present.count(*label))
            throw InputError(concat("conductivity table: '", key, "' is no tissue of the mesh (tissues: ",
                                    known_tissues(mesh, present), "); use a label number or one of these names"));
        if (const auto [first, inserted] = key_of.emplace(*label, key); !inserted)
            throw InputError(concat("conductivity table: '", first->second, "' and '", key, "' both name tissue ",
                                    *label, " (", name_of(mesh, *label), "); give it once"));
        result.by_label[*label] = tensor;
    }
    apply_patterns(mesh, table, present, result);
    for (Label label : present) {
        if (result.by_label.count(label)) continue;
        const auto& defaults = default_head_conductivities();
        const auto found = defaults.find(lower(name_of(mesh, label)));
        if (!use_defaults || found == defaults.end())
            throw InputError(concat("tissue ", label, " (", name_of(mesh, label), ") has no conductivity; add \"",
                                    name_of(mesh, label), "\": S/m to the conductivity table"));
        result.by_label[label] = isotropic(found->second);
    }
    return result;
}

const Mat3& Conductivities::of(Label tissue, std::size_t tet) const
{
    const auto found = by_label.find(tissue);
    if (found == by_label.end())
        throw InputError(
            concat("tissue ", tissue, " (tet ", tet, ") has no conductivity; add it to the conductivity table"));
    return found->second;
}

} // namespace tissuemesh::fem

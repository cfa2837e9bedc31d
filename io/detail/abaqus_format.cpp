#include "io/detail/abaqus_format.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <charconv>
#include <map>
#include <set>
#include <unordered_map>

#include "core/error.h"
#include "io/detail/abaqus_surfaces.h"
#include "io/detail/byte_reader.h"
#include "io/detail/msh_common.h"
#include "io/detail/text_records.h"

namespace tissuemesh::io::detail {
namespace {

std::string upper(std::string_view text)
{
    std::string out(text);
    for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return out;
}

std::string trimmed(std::string_view text)
{
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
    return std::string(text);
}

/// Comma-separated fields of a line, trimmed (a trailing comma gives no empty field).
std::vector<std::string> fields(std::string_view line)
{
    std::vector<std::string> out;
    for (std::size_t start = 0; start <= line.size();) {
        const std::size_t comma = std::min(line.find(',', start), line.size());
        out.push_back(trimmed(line.substr(start, comma - start)));
        start = comma + 1;
    }
    if (!out.empty() && out.back().empty()) out.pop_back();
    return out;
}

/// The value of `KEY=value` among a keyword line's fields (case-insensitive key), or "".
std::string parameter(const std::vector<std::string>& keyword, const std::string& key)
{
    for (const std::string& field : keyword) {
        const std::size_t equals = field.find('=');
        if (equals != std::string::npos && upper(trimmed(field.substr(0, equals))) == key)
            return trimmed(field.substr(equals + 1));
    }
    return "";
}

/// An element set name Abaqus accepts (letters, digits and '_', starting with a letter) that ends with the
/// label, so that any reader can tell the tissue: "grey_matter_4", "tissue_4".
std::string set_name(const TetMesh& mesh, Label label)
{
    const auto found = mesh.names.find(label);
    std::string name = found != mesh.names.end() ? found->second.substr(0, 50) : "";
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    if (name.empty() || !std::isalpha(static_cast<unsigned char>(name[0])))
        name = "tissue" + (name.empty() ? "" : "_" + name);
    return concat(name, "_", label);
}

long long number(const std::string& field, const ByteReader& in, const char* expected)
{
    long long value = 0;
    const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
    if (error != std::errc() || end != field.data() + field.size())
        in.fail(concat("expected ", expected, " but found \"", field.substr(0, 40), "\""), "the file is corrupt");
    return value;
}

double real(const std::string& field, const ByteReader& in)
{
    double value = 0;
    const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
    if (error != std::errc() || end != field.data() + field.size())
        in.fail(concat("expected a coordinate but found \"", field.substr(0, 40), "\""), "the file is corrupt");
    return value;
}

/// The label of element set `name`: from our comments, else its trailing number, else its position.
Label label_of_set(const std::string& name, const std::map<std::string, Label>& commented, Label position)
{
    if (const auto found = commented.find(upper(name)); found != commented.end()) return found->second;
    std::size_t digits = name.size();
    while (digits > 0 && std::isdigit(static_cast<unsigned char>(name[digits - 1]))) --digits;
    if (digits < name.size() && name.size() - digits <= 5) {
        const unsigned long value = std::stoul(name.substr(digits));
        if (value <= 65535) return static_cast<Label>(value);
    }
    return position;
}

} // namespace

std::string format_abaqus(const TetMesh& mesh, const std::string& what)
{
    std::map<Label, std::vector<std::size_t>> by_tissue;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) by_tissue[mesh.tet_labels[t]].push_back(t);
    std::string out = "*HEADING\ntissuemesh tetrahedral mesh, lengths in mm\n";
    for (const auto& [label, tets] : by_tissue) {
        const auto found = mesh.names.find(label);
        out += concat("** tissuemesh elset ", set_name(mesh, label), " label ", label, "\n");
        if (found != mesh.names.end()) out += concat("** tissuemesh tissue ", label, " ", found->second, "\n");
    }
    out += "*NODE\n";
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        out += concat(v + 1);
        for (const double c : mesh.vertices[v]) out += ", ", append_real(out, c);
        out += '\n';
    }
    long long id = 1;
    std::vector<long long> element_of_tet(mesh.tets.size());
    for (const auto& [label, tets] : by_tissue) {
        out += concat("*ELEMENT, TYPE=C3D4, ELSET=", set_name(mesh, label), "\n");
        for (const std::size_t t : tets) {
            const Tet& tet = mesh.tets[t];
            element_of_tet[t] = id;
            out += concat(id++, ", ", tet[0] + 1, ", ", tet[1] + 1, ", ", tet[2] + 1, ", ", tet[3] + 1, '\n');
        }
    }
    return out + format_abaqus_surfaces(mesh, element_of_tet, what);
}

TetMesh parse_abaqus(const std::string& text, const std::string& what)
{
    ByteReader in(text, what);
    TetMesh mesh;
    read_name_comments(text, "**", mesh.names);
    NodeIndex nodes;
    std::vector<long long> node_numbers;
    std::vector<std::array<long long, 4>> corners;                    // node numbers, resolved once all nodes are read
    std::unordered_map<long long, std::size_t> tet_of;                // element number -> tet
    std::vector<std::pair<std::string, std::vector<long long>>> sets; // in file order
    std::map<std::string, Label> commented;
    std::map<std::string, LabelPair> surface_pairs; // by surface name, upper case
    std::vector<AbaqusSurface> surfaces;
    constexpr std::size_t npos = std::string::npos;
    std::size_t element_set = npos; // the set an *ELEMENT block's own ELSET= names
    enum class Block { none, node_lines, tets, elset, generate, surface } block = Block::none;
    while (in.remaining() > 0) {
        const std::string line = trimmed(in.rest_of_line());
        if (line.empty()) continue;
        if (line.rfind("**", 0) == 0) {
            std::string comment = line.substr(2);
            char set[128] = {};
            unsigned label = 0;
            unsigned to = 0;
            if (std::sscanf(comment.c_str(), " tissuemesh elset %127s label %u", set, &label) == 2 && label <= 65535)
                commented[upper(set)] = static_cast<Label>(label);
            if (std::sscanf(comment.c_str(), " tissuemesh surface %127s from %u to %u", set, &label, &to) == 3 &&
                label <= 65535 && to <= 65535)
                surface_pairs[upper(set)] = {static_cast<Label>(label), static_cast<Label>(to)};
            continue;
        }
        const std::vector<std::string> parts = fields(line);
        if (line[0] == '*') {
            const std::string keyword = upper(parts[0]);
            const std::string type = upper(parameter(parts, "TYPE")), elset = parameter(parts, "ELSET");
            block = Block::none;
            element_set = npos;
            if (keyword == "*NODE") block = Block::node_lines;
            if (keyword == "*SURFACE" && (type.empty() || type == "ELEMENT")) {
                surfaces.push_back({parameter(parts, "NAME"), {}});
                block = Block::surface;
            }
            if (keyword == "*ELEMENT" && (type == "C3D4" || type == "C3D10")) block = Block::tets;
            if ((keyword == "*ELEMENT" && block == Block::tets) || keyword == "*ELSET") {
                if (!elset.empty()) sets.push_back({elset, {}});
                if (keyword == "*ELEMENT" && !elset.empty()) element_set = sets.size() - 1;
                if (keyword == "*ELSET") {
                    const bool generate = std::any_of(parts.begin(), parts.end(),
                                                      [](const std::string& p) { return upper(p) == "GENERATE"; });
                    block = elset.empty() ? Block::none : generate ? Block::generate : Block::elset;
                }
            }
            continue;
        }
        if (block == Block::node_lines) {
            if (parts.size() < 4) in.fail("a node line has fewer than 4 fields", "write \"number, x, y, z\"");
            node_numbers.push_back(number(parts[0], in, "a node number"));
            mesh.vertices.push_back({real(parts[1], in), real(parts[2], in), real(parts[3], in)});
        } else if (block == Block::tets) {
            if (parts.size() < 5) in.fail("a tet line has fewer than 5 fields", "write one element per line");
            const long long id = number(parts[0], in, "an element number");
            std::array<long long, 4> c{};
            for (std::size_t i = 0; i < 4; ++i) c[i] = number(parts[i + 1], in, "a node number");
            tet_of[id] = corners.size();
            corners.push_back(c);
            if (element_set != npos) sets[element_set].second.push_back(id);
        } else if (block == Block::surface) {
            if (parts.size() < 2 || parts[1].size() < 2 || std::toupper(static_cast<unsigned char>(parts[1][0])) != 'S')
                in.fail(concat("surface ", surfaces.back().name, " has a line that is not \"element set, S<face>\""),
                        "write e.g. \"SKIN, S2\"");
            surfaces.back().entries.push_back({parts[0], static_cast<int>(std::clamp<long long>(
                                                             number(parts[1].substr(1), in, "a face id"), -1, 99))});
        } else if (block == Block::elset || block == Block::generate) {
            std::vector<long long>& members = sets.back().second;
            std::vector<long long> values;
            for (const std::string& p : parts) values.push_back(number(p, in, "an element number"));
            if (block == Block::elset) members.insert(members.end(), values.begin(), values.end());
            else if (values.size() >= 2) {
                const long long step = values.size() > 2 ? values[2] : 1;
                if (step < 1 || values[1] < values[0] ||
                    values[1] - values[0] > static_cast<long long>(corners.size()) * step + step)
                    in.fail("an ELSET GENERATE range is not valid", "write first, last, step with step >= 1");
                for (long long e = values[0]; e <= values[1]; e += step) members.push_back(e);
            }
        }
    }
    for (const long long n : node_numbers) nodes.add(n);
    nodes.finish(in);
    mesh.tets.reserve(corners.size());
    std::vector<Tet> resolved; // in the file's corner order, which the face ids refer to
    resolved.reserve(corners.size());
    for (const auto& c : corners) {
        resolved.push_back({nodes.at(c[0], in), nodes.at(c[1], in), nodes.at(c[2], in), nodes.at(c[3], in)});
        add_tet(mesh, resolved.back(), 0);
    }
    std::set<std::string> face_sets; // element sets that surfaces use: faces, not tissues
    for (const AbaqusSurface& surface : surfaces)
        for (const auto& entry : surface.entries) face_sets.insert(upper(entry.first));
    Label position = 0;
    for (const auto& [name, members] : sets) {
        const bool has_tets =
            std::any_of(members.begin(), members.end(), [&](long long e) { return tet_of.count(e) > 0; });
        if (!has_tets || face_sets.count(upper(name))) continue;
        const Label label = label_of_set(name, commented, ++position);
        for (const long long e : members)
            if (const auto found = tet_of.find(e); found != tet_of.end()) mesh.tet_labels[found->second] = label;
    }
    add_abaqus_faces(mesh, {surfaces, sets, tet_of, resolved, surface_pairs}, in);
    return mesh;
}

} // namespace tissuemesh::io::detail

#include "io/simnibs_tags.h"

#include <algorithm>
#include <cctype>
#include <set>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"

namespace tissuemesh::io {
namespace fs = std::filesystem;
namespace {

/// A key that is a label number ("6", "06"), or -1.
long label_key(const std::string& key)
{
    if (key.empty() || key.size() > 5 || key.find_first_not_of("0123456789") != std::string::npos) return -1;
    const long value = std::stol(key);
    return value <= 65535 ? value : -1;
}

std::string known_names()
{
    std::string text;
    for (const SimnibsTissue& tissue : simnibs_tissues())
        text += concat(text.empty() ? "" : ", ", tissue.accepted_names.front(), " ", tissue.tag);
    return text;
}

/// Where a tissue's tag came from: the user's table or the built-in names.
struct Assigned {
    int tag = 0;
    bool from_table = false;
};

} // namespace

const std::vector<SimnibsTissue>& simnibs_tissues()
{
    static const std::vector<SimnibsTissue> tissues = {
        {1, "WM", {"white matter", "wm", "white", "cerebral white matter"}},
        {2, "GM", {"grey matter", "gray matter", "gm", "grey", "gray", "cortex", "cerebral cortex"}},
        {3, "CSF", {"csf", "cerebrospinal fluid"}},
        {4, "Bone", {"bone", "skull"}},
        {5, "Scalp", {"scalp", "skin"}},
        {6, "Eye_balls", {"eyes", "eye", "eye balls", "eyeballs"}},
        {7, "Compact_bone", {"compact bone", "cortical bone"}},
        {8, "Spongy_bone", {"spongy bone", "cancellous bone", "trabecular bone"}},
        {9, "Blood", {"blood", "blood vessels", "vessels"}},
        {10, "Muscle", {"muscle"}},
        {11, "Edema", {"edema", "oedema"}},
        {12, "Fat", {"fat"}},
    };
    return tissues;
}

std::string simnibs_name_key(const std::string& name)
{
    std::string key;
    for (const char c : name) {
        const char lower = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        const bool space = lower == '_' || lower == '-' || std::isspace(static_cast<unsigned char>(lower));
        if (space && (key.empty() || key.back() == ' ')) continue;
        key += space ? ' ' : lower;
    }
    if (!key.empty() && key.back() == ' ') key.pop_back();
    return key;
}

SimnibsTagTable read_simnibs_tag_table(const fs::path& path)
{
    require_readable_file(path);
    const std::string name = path.string();
    if (fs::file_size(path) > (1u << 20))
        throw IoError(concat(name, ": over 1 MiB is too large for a tissue tag table; check the file name"));
    const nlohmann::json document = nlohmann::json::parse(read_file_bytes(path), nullptr, false);
    if (document.is_discarded() || !document.is_object())
        throw IoError(concat(name, ": not a JSON object; write the tags as {\"air cavities\": 13, \"6\": 13}"));
    SimnibsTagTable table;
    std::set<std::string> seen;
    for (const auto& [key, value] : document.items()) {
        const std::string normal = label_key(key) >= 0 ? std::to_string(label_key(key)) : simnibs_name_key(key);
        if (normal.empty()) throw InputError(concat(name, ": an empty key; keys are tissue names or label numbers"));
        if (!seen.insert(normal).second)
            throw InputError(concat(name, ": \"", key,
                                    "\" is given twice (names are compared in any case, labels by value); keep one"));
        if (!value.is_number_integer() || value.get<long long>() < 1 || value.get<long long>() > 999)
            throw InputError(concat(name, ": the tag of \"", key, "\" is ", value.dump(),
                                    "; SimNIBS volume tags are integers "
                                    "1..999 (its surfaces take 1000 + the tag)"));
        table[key] = value.get<int>();
    }
    return table;
}

std::map<Label, int> simnibs_tags(const TetMesh& mesh, const SimnibsTagTable& table)
{
    const std::set<Label> labels(mesh.tet_labels.begin(), mesh.tet_labels.end());
    auto name_of = [&](Label label) {
        const auto found = mesh.names.find(label);
        return found != mesh.names.end() ? found->second : std::to_string(label);
    };
    std::map<Label, Assigned> assigned;
    std::set<std::string> used_keys;
    for (const Label label : labels) {
        const std::string key = simnibs_name_key(name_of(label));
        for (const auto& [entry, tag] : table)
            if (label_key(entry) == long{label} || (label_key(entry) < 0 && simnibs_name_key(entry) == key)) {
                if (!assigned.count(label) || label_key(entry) >= 0) assigned[label] = {tag, true};
                used_keys.insert(entry);
            }
        if (assigned.count(label)) continue;
        for (const SimnibsTissue& tissue : simnibs_tissues())
            if (std::find(tissue.accepted_names.begin(), tissue.accepted_names.end(), key) !=
                tissue.accepted_names.end())
                assigned[label] = {tissue.tag, false};
    }
    std::string tissues;
    for (const Label label : labels)
        tissues += concat(tissues.empty() ? "" : ", ", "\"", name_of(label), "\" (", label, ")");
    for (const auto& [entry, tag] : table)
        if (!used_keys.count(entry))
            throw InputError(
                concat("the tag table's key \"", entry, "\" names no tissue of the mesh; its tissues are ", tissues));
    std::string missing;
    for (const Label label : labels)
        if (!assigned.count(label))
            missing += concat(missing.empty() ? "" : ", ", "\"", name_of(label), "\" (label ", label, ")");
    if (!missing.empty())
        throw InputError(
            concat("no SimNIBS tag for ", missing, "; SimNIBS knows ", known_names(),
                   "; map the others in a table, e.g. --tissue-tags tags.json with {\"",
                   name_of(*std::find_if(labels.begin(), labels.end(), [&](Label l) { return !assigned.count(l); })),
                   "\": 13}"));
    std::map<Label, int> tags;
    for (const auto& [label, a] : assigned) {
        for (const auto& [other, b] : assigned)
            if (other < label && a.tag == b.tag && !(a.from_table && b.from_table))
                throw InputError(
                    concat("\"", name_of(other), "\" and \"", name_of(label), "\" would both get SimNIBS tag ", a.tag,
                           "; to merge them, give both that tag in --tissue-tags, else map one elsewhere"));
        tags[label] = a.tag;
    }
    return tags;
}

int simnibs_face_tag(int a, int b)
{
    static const int hierarchy[] = {1, 2, 9, 3, 4, 8, 7, 6, 11, 10, 12, 5};
    const auto rank = [](int tag) {
        const auto* found = std::find(std::begin(hierarchy), std::end(hierarchy), tag);
        return found != std::end(hierarchy) ? static_cast<long>(found - std::begin(hierarchy)) : 1000L + tag;
    };
    return 1000 + (rank(a) <= rank(b) ? a : b);
}

} // namespace tissuemesh::io

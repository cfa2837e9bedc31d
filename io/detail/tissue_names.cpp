#include "io/detail/tissue_names.h"

#include <limits>

#include "core/error.h"

namespace tissuemesh::io::detail {

namespace {

Label parse_label_key(const std::string& name, const std::string& key)
{
    std::size_t used = 0;
    long value = -1;
    try {
        value = std::stol(key, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != key.size() || key.empty() || value < 0 || value > std::numeric_limits<Label>::max())
        throw InputError(concat(name, ": tissue-name key '", key,
                                "' is not a label number in 0..65535; "
                                "write the names as {\"1\": \"scalp\", ...}"));
    return static_cast<Label>(value);
}

} // namespace

TissueNames parse_tissue_names(const std::string& name, const nlohmann::json& table)
{
    if (!table.is_object())
        throw InputError(concat(name,
                                ": tissue names must be a JSON object such as {\"1\": \"scalp\"}; "
                                "found ",
                                table.type_name()));
    TissueNames names;
    for (const auto& [key, value] : table.items()) {
        if (!value.is_string())
            throw InputError(
                concat(name, ": the name of label ", key, " is not a string; write it as \"", key, "\": \"scalp\""));
        names[parse_label_key(name, key)] = value.get<std::string>();
    }
    return names;
}

} // namespace tissuemesh::io::detail

// Tissue-name tables in JSON ({"1": "scalp", ...}), shared by read_tissue_names() and the raw + JSON reader.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "core/label_image.h"

namespace tissuemesh::io::detail {

/// Converts a JSON object {"<label>": "<name>"} to tissue names; `name` is the file for messages.
/// @throws InputError when `table` is not an object, a key is not a label in 0..65535, or a name is
///         not a string
TissueNames parse_tissue_names(const std::string& name, const nlohmann::json& table);

} // namespace tissuemesh::io::detail

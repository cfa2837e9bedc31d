// Reading a conductivity table (S/m per tissue) from JSON.
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "core/vec3.h"

namespace tissuemesh::io {

/// The largest table read (1 MiB, some 7 000 tensors): a bigger file is not a tissue table.
inline constexpr std::size_t max_conductivity_table_bytes = 1u << 20;

/// Reads a conductivity table: a JSON object from tissue names or label numbers to S/m, each value a
/// positive number (isotropic) or a tensor as 9 numbers (row-major) or 3 rows of 3:
///     {"scalp": 0.43, "3": 1.79, "white": [[0.65, 0, 0], [0, 0.065, 0], [0, 0, 0.065]]}
/// Returns key -> tensor (row-major, S/m; a number s becomes s * identity), the keys as written: matching
/// them to a mesh's tissues, and checking that a tensor is symmetric positive definite, is
/// fem::resolve_conductivities()'s job (the map has the type of fem::ConductivityTable; io depends on core
/// only). The file's size is checked before it is read, and its nesting before it is parsed.
/// @throws IoError when the file is missing, empty, over max_conductivity_table_bytes, not valid JSON
///         (the message has the line and column), nested deeper than a table, or not an object
/// @throws InputError when the table is empty, a key is empty or given twice (names compared in any case,
///         label numbers by value: "brain" and "Brain", "3" and "03"), or a value is not a positive finite
///         number nor a tensor of 9 finite numbers
/// Every message is one line: "<file>: <problem>; <fix>".
std::map<std::string, Mat3> read_conductivity_table(const std::filesystem::path& path);

} // namespace tissuemesh::io

// Reading sensor positions (EEG electrodes that measure) from a CSV file.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "core/vec3.h"

namespace tissuemesh::io {

/// One row of a sensor file.
struct SensorRow {
    Vec3 position_mm{};   ///< world mm (the mesh's coordinates)
    std::string name;     ///< "Fp1"; empty when the file has no name column
    std::size_t line = 0; ///< 1-based line in the file, for messages
};

/// The most sensors a file may hold: far more than any EEG cap (256); tm-solve's nearest-node lookup
/// costs sensors x surface nodes.
inline constexpr std::size_t max_sensors = 100'000;

/// Reads a sensor file: a header `x,y,z` (mm), optionally with a `name` column, in any order and case,
/// then one sensor per line:
///     name,x,y,z
///     Fp1,-29.4,83.9,-7.0
/// Blank lines and lines starting with '#' are skipped; Windows line ends and a UTF-8 byte-order mark
/// are accepted; names, when given, are unique. No allocation before the file's size is checked
/// (at most 64 MiB) and none beyond what its lines hold.
/// @throws IoError (one line: "<file> line <n>: <problem>; <fix>") when the file is missing, empty,
///         larger than 64 MiB, has no header, unknown, repeated or missing columns, a row with the wrong
///         number of fields, a coordinate that is not a finite number, an empty, repeated or unprintable
///         name, no rows, or more than max_sensors rows
std::vector<SensorRow> read_sensors(const std::filesystem::path& path);

} // namespace tissuemesh::io

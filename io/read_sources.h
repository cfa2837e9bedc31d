// Reading dipole source positions (and fixed orientations) for lead fields from a CSV file.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/vec3.h"

namespace tissuemesh::io {

/// One row of a source file.
struct SourceRow {
    Vec3 position_mm{};              ///< world mm (the mesh's coordinates)
    std::optional<Vec3> orientation; ///< unit vector when the file fixes orientations (normalised here)
    std::string name;                ///< empty when the file has no name column
    std::size_t line = 0;            ///< 1-based line in the file, for messages
};

/// The most sources a file may hold: a 2 mm grid in the grey matter of a head has about 50 000; each costs
/// the lead field three columns.
inline constexpr std::size_t max_sources = 500'000;

/// Reads a source file: a header `x,y,z` (mm), optionally with `nx,ny,nz` (an orientation per source, any
/// length but not zero; normalised) and a `name` column, in any order and case, then one source per line:
///     x,y,z,nx,ny,nz
///     12.5,-30,55.2,0,0,1
/// Blank lines and '#' lines are skipped; the rules of tm-solve's sensor files apply (read_sensors.h).
/// With nx,ny,nz in the header every row must give all three.
/// @throws IoError (one line: "<file> line <n>: <problem>; <fix>") for everything read_sensors() refuses,
///         an orientation with one or two of its three fields given, or more than max_sources rows
/// @throws InputError for a zero orientation
std::vector<SourceRow> read_sources(const std::filesystem::path& path);

} // namespace tissuemesh::io

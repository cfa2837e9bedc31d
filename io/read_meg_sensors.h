// Reading MEG sensors (magnetometers, and gradiometers as pairs of coils) from a CSV file.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/vec3.h"

namespace tissuemesh::io {

/// One MEG sensor: a magnetometer measures B . normal at its position (T); a gradiometer measures the
/// difference of two such coils with the same normal, B(position) . normal - B(second_coil) . normal (T).
struct MegSensorRow {
    Vec3 position_mm{};                 ///< world mm, outside the head
    Vec3 normal{};                      ///< unit vector (normalised here)
    std::optional<Vec3> second_coil_mm; ///< a gradiometer's second coil, world mm; none for a magnetometer
    std::string name;                   ///< empty when the file has no name column
    std::size_t line = 0;               ///< 1-based line in the file, for messages
};

/// The most sensors a file may hold (whole-head systems have about 300).
inline constexpr std::size_t max_meg_sensors = 10'000;

/// Reads an MEG sensor file: a header `x,y,z,nx,ny,nz` (mm, unitless), optionally with `x2,y2,z2` (mm: the
/// second coil of a gradiometer; blank in the rows of magnetometers) and `name`, in any order and case:
///     name,x,y,z,nx,ny,nz
///     MEG0111,-106.9,10.2,56.1,-0.98,0.1,0.17
/// The rules of tm-solve's sensor files apply (read_sensors.h).
/// @throws IoError (one line: "<file> line <n>: <problem>; <fix>") for everything read_sensors() refuses,
///         a second coil with one or two of its fields given, or more than max_meg_sensors rows
/// @throws InputError for a zero normal, or a second coil on the first
std::vector<MegSensorRow> read_meg_sensors(const std::filesystem::path& path);

} // namespace tissuemesh::io

// Reading an electrode montage (tDCS/tACS, EIT: scalp patches that inject current) from a CSV file.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "core/vec3.h"

namespace tissuemesh::io {

/// One electrode of a montage.
struct ElectrodeRow {
    Vec3 centre_mm{};     ///< patch centre, world mm (the mesh's coordinates; need not lie on the surface)
    double radius_mm = 0; ///< patch radius, mm, > 0
    double current_a = 0; ///< current into the body, A (negative: out of it; 0: a passive patch)
    std::string name;     ///< "C3"; empty when the file has no name column
    std::size_t line = 0; ///< 1-based line in the file, for messages
};

/// The most electrodes a montage may hold: far more than any cap (HD-EEG has 256); each costs the
/// solver a pass over the surface.
inline constexpr std::size_t max_electrodes = 10'000;

/// Reads a montage: a header `x,y,z,radius_mm,current_a` (mm, mm, A), optionally with a `name`
/// column, in any order and case, then one electrode per line:
///     name,x,y,z,radius_mm,current_a
///     C3,-52.1,-18.9,96.4,12.5,+0.002
///     Fp2,27.3,88.1,29.0,12.5,-0.002
/// Blank lines and lines starting with '#' are skipped; Windows line ends and a UTF-8 byte-order mark
/// are accepted; names, when given, are unique. Whether the currents sum to zero and whether each patch
/// touches the mesh are the solver's checks (they need the mesh). No allocation before the file's size
/// is checked (at most 64 MiB) and none beyond what its lines hold.
/// @throws IoError (one line: "<file> line <n>: <problem>; <fix>") when the file is missing, empty,
///         larger than 64 MiB, has no header, unknown, repeated or missing columns (current_ma or
///         radius_cm get a hint on units), a row with the wrong number of fields, a value that is not a
///         finite number, an empty, repeated or unprintable name, no rows, or more than max_electrodes rows
/// @throws InputError when a radius is not positive
std::vector<ElectrodeRow> read_electrodes(const std::filesystem::path& path);

/// The same for files that only place the patches (tm-leadfield's tDCS electrodes): the current_a column may be
/// left out, or a field left blank (0 A).
/// @throws what read_electrodes() throws, but for a missing current_a
std::vector<ElectrodeRow> read_electrode_patches(const std::filesystem::path& path);

} // namespace tissuemesh::io

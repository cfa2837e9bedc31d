// Reading and writing interface complexes (triangle surfaces with a tissue pair per triangle).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/interface_complex.h"

namespace tissuemesh::io {

/// Writes `complex` atomically. By extension: `.ply` (binary little-endian, per-face `label_a label_b`
/// as uchar/ushort properties, tissue names as comments), `.vtp` (ParaView, cell data label_a, label_b),
/// `.obj` (label pairs as groups `g tissues_<from>_<to>`), `.off` and `.stl` (binary; geometry only).
/// `ply_comments`: more `comment` lines for a `.ply` header (one line each; other formats have no place for them).
/// @throws IoError when the file cannot be written or the extension is unknown
void write_surface(const InterfaceComplex& complex, const std::filesystem::path& path,
                   const std::vector<std::string>& ply_comments = {});

/// Reads a complex written by write_surface() (`.ply`, `.vtp` and `.obj` with label pairs; `.off`, `.stl`
/// (binary or ASCII) and files without labels give every triangle the pair {1, 0}: one tissue against
/// background).
/// @throws IoError on unreadable or malformed files, InputError on dangling indices or NaN coordinates
InterfaceComplex read_surface(const std::filesystem::path& path);

} // namespace tissuemesh::io

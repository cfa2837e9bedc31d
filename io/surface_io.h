// Reading and writing interface complexes (triangle surfaces with a tissue pair per triangle).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/interface_complex.h"

namespace tissuemesh::io {

/// Variants of the surface formats that have them.
struct SurfaceWriteOptions {
    /// `.ply` and `.stl` as ASCII instead of binary. meshio reads our per-face labels from ASCII PLY only: its
    /// binary PLY reader takes each face property as one column after the other, not face by face.
    bool ascii = false;
    /// More `comment` lines for a `.ply` header (one line each; other formats have no place for them).
    std::vector<std::string> ply_comments;
};

/// Writes `complex` atomically. By extension: `.ply` (binary little-endian or ASCII, per-face `label_a label_b`
/// as uint16 properties, tissue names as comments), `.vtp` (ParaView, cell data label_a, label_b),
/// `.obj` (label pairs as groups `g tissues_<from>_<to>`), `.off` and `.stl` (binary or ASCII; geometry only).
/// @throws IoError when the file cannot be written or the extension is unknown
void write_surface(const InterfaceComplex& complex, const std::filesystem::path& path,
                   const SurfaceWriteOptions& options);

/// The same, binary, with `ply_comments` in a `.ply` header.
void write_surface(const InterfaceComplex& complex, const std::filesystem::path& path,
                   const std::vector<std::string>& ply_comments = {});

/// Reads a complex written by write_surface() (`.ply`, `.vtp` and `.obj` with label pairs; `.off`, `.stl`
/// (binary or ASCII) and files without labels give every triangle the pair {1, 0}: one tissue against
/// background).
/// @throws IoError on unreadable or malformed files, InputError on dangling indices or NaN coordinates
InterfaceComplex read_surface(const std::filesystem::path& path);

} // namespace tissuemesh::io

// Writing an interface complex while it is produced, without ever holding it whole (binary PLY).
#pragma once

#include <filesystem>
#include <functional>

#include "core/interface_sink.h"

namespace tissuemesh::io {

/// Writes to `path` (.ply) the complex that `produce` hands, piece by piece, to the sink it is given:
/// byte for byte the file write_surface() writes for the collected complex, while holding one piece at a
/// time. Vertex and face records go to two side files next to `path` while `produce` runs; then the
/// header (which needs the counts) is written and the two are copied under it. Outputs are valid or
/// absent: `path` appears only when complete; on any exception the temporary and side files are removed
/// and the exception propagates. Each piece is checked as write_surface() checks a complex (indices of
/// vertices handed so far, two distinct tissues per triangle, finite coordinates).
/// Disk: the side files take as much again as the PLY file until it is complete.
/// @throws IoError when `path` is not .ply or cannot be written; InputError on an invalid piece (naming
///         `path`); whatever `produce` throws
void write_surface_streamed(const std::filesystem::path& path, const std::function<void(InterfaceSink& sink)>& produce);

} // namespace tissuemesh::io

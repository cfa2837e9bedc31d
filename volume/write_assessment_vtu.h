// Writing a tet mesh with its assessment as VTK cell data (ParaView).
#pragma once

#include <filesystem>

#include "core/tet_mesh.h"
#include "volume/assess.h"

namespace tissuemesh::volume {

/// Writes `mesh` as a VTK XML unstructured grid (ASCII, .vtu) with one cell-data array per assessed
/// field: tissue (the mesh's current label), majority, error_volume_mm3, majority_error_volume_mm3,
/// quality_key, voxel_count, sampled, volume_mm3, min_dihedral_deg, radius_edge_ratio, aspect_ratio.
/// Non-finite values (degenerate tets) are written as +-1e30, which VTK's ASCII reader accepts.
/// The file is written atomically.
/// @throws InputError when `assessment` does not have one entry per tet of `mesh`
/// @throws IoError when the file cannot be written
void write_assessment_vtu(const TetMesh& mesh, const Assessment& assessment, const std::filesystem::path& path);

} // namespace tissuemesh::volume

// A solved potential as a VTK XML unstructured grid (.vtu, ASCII), for ParaView.
// Lives in fem/ for now: io/ writes meshes only and does not know about FEM fields.
#pragma once

#include <filesystem>
#include <vector>

#include "core/tet_mesh.h"
#include "fem/compute_fields.h"

namespace tissuemesh::fem {

/// Writes `mesh` (points in mm) with point data "potential_V" and cell data "tissue", "E_V_per_m",
/// "J_A_per_m2", "E_magnitude_V_per_m" and, when given (#T), "error_indicator" (estimate_error()), atomically.
/// @throws InputError when the array sizes do not match the mesh; IoError when the file cannot be written
void write_solution_vtu(const std::filesystem::path& path, const TetMesh& mesh, const std::vector<double>& potential_v,
                        const TetFields& fields, const std::vector<double>& error_indicator = {});

} // namespace tissuemesh::fem

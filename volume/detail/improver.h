// The improver's schedule on one mesh (improve_mesh() runs it on the whole mesh or on its parts side by side):
// passes over the tets below the target, worst first, each tet trying flips, then smoothing of its nodes, then
// node insertion.
#pragma once

#include <map>
#include <vector>

#include "core/progress.h"
#include "core/tet_mesh.h"
#include "volume/detail/surface_reference.h"
#include "volume/improve_mesh.h"

namespace tissuemesh::surface::detail {
class VoxelSides;
} // namespace tissuemesh::surface::detail

namespace tissuemesh::volume::detail {

/// Improves `mesh` in place against `reference` (one thread), with `sides` (or null) judging interface edits against
/// the voxels (ImproveOptions::voxel_image), adding its counts to `report` (not its figures or
/// times). Nodes flagged in `frozen` (per node) never change, nor any face or edge all of whose nodes are
/// frozen (WorkMesh); with `seeds` (per node), only the tets at a flagged node are queued at the start of a
/// pass (tets the edits make or reshape join the queue as always). `volume_allowance_mm3`: per tissue, how far its
/// volume in `mesh` may drift (mm^3); a tissue it does not list may drift ImproveOptions::max_volume_change of its
/// volume in `mesh` (right for a whole mesh and its parts; improve_mesh() gives its last round, a few hundred tets,
/// that fraction of the whole mesh's volumes). `last`: no later round follows (a whole mesh, or improve_mesh()'s last
/// round), so a tet left under half the target gets its edits again with the faces allowed further from the reference
/// (improver.cpp).
void improve_in_place(TetMesh& mesh, const SurfaceReference& reference, const surface::detail::VoxelSides* sides,
                      const ImproveOptions& options, ImproveReport& report, std::vector<char> frozen = {},
                      std::vector<char> seeds = {}, const std::map<Label, double>& volume_allowance_mm3 = {},
                      bool last = true, const Progress& progress = {});

/// improve_mesh() against a reference built before (tetrahedralize() builds it while TetGen runs); the report's
/// times leave its building out.
ImproveReport improve_mesh_against(TetMesh& mesh, const SurfaceReference& reference, const ImproveOptions& options,
                                   const Progress& progress = {});

} // namespace tissuemesh::volume::detail

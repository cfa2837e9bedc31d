// The improver's schedule on one mesh (improve_mesh() runs it on the whole mesh or on its parts side by side):
// passes over the tets below the target, worst first, each tet trying flips, then smoothing of its nodes, then
// node insertion.
#pragma once

#include <algorithm>
#include <cstddef>
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

/// The last round (improve_in_place()'s `last`) takes on again every tet left under this fraction of
/// ImproveOptions::target_dihedral_deg (0.95 of 21: 19.95 degrees), with its faces allowed further from the reference
/// where no edit lifts it (improver.cpp). Measured after tm-tetra on bench/run's and real-heads' surfaces (1 mm sphere
/// head, 2 mm sphere head, thin, torso, liver, 1 mm usc19-5 head), smallest angle: at 0.5 (until the twenty-third
/// session) 15.59, 14.67, 15.75, 13.91, 17.17, 11.74; at 0.95 19.85, 19.95, 19.41, 15.57, 18.40, 13.18; the improver
/// 0.7 s longer on the head (its last round; 7.1-7.8 -> 7.9-8.5 s), as long as before on the torso.
constexpr double rescue_fraction = 0.95;
/// Under this fraction of the target, the last pass of every round does not ask the voxels
/// (ImproveOptions::voxel_image) and the bands around the parts' cuts take on the tet wherever it is
/// (improve_mesh.cpp): the floor is 10 degrees, and a few edits there cost the Dice little.
constexpr double waiver_fraction = 0.5;
/// The last round's bar (degrees) for a mesh of `tets` tets, `under` of them under rescue_fraction of the target:
/// that fraction when they are few (at most 1 000, or a thousandth of the tets), else waiver_fraction, as before the
/// twenty-third session. The last round is one part on one core: the bench and real volumes leave it 15-366 such tets
/// (0.01-0.5 s), but the coarse 4-shell icosphere head of the fem tests (50 mm triangles over a 2 mm CSF, 31 k tets)
/// left 5 133, and the round over them and their rings took 35 s.
inline double last_round_bar_deg(std::size_t under, std::size_t tets, double target_deg)
{
    return (under <= std::max<std::size_t>(1000, tets / 1000) ? rescue_fraction : waiver_fraction) * target_deg;
}

/// Improves `mesh` in place against `reference` (one thread), with `sides` (or null) judging interface edits against
/// the voxels (ImproveOptions::voxel_image), adding its counts to `report` (not its figures or
/// times). Nodes flagged in `frozen` (per node) never change, nor any face or edge all of whose nodes are
/// frozen (WorkMesh); with `seeds` (per node), only the tets at a flagged node are queued at the start of a
/// pass (tets the edits make or reshape join the queue as always). `volume_allowance_mm3`: per tissue, how far its
/// volume in `mesh` may drift (mm^3); a tissue it does not list may drift ImproveOptions::max_volume_change of its
/// volume in `mesh` (right for a whole mesh and its parts; improve_mesh() gives its last round, a few hundred tets,
/// that fraction of the whole mesh's volumes). `last`: no later round follows (a whole mesh, or improve_mesh()'s last
/// round), so a tet left under rescue_fraction of the target gets its edits again with the faces allowed further from
/// the reference (improver.cpp).
void improve_in_place(TetMesh& mesh, const SurfaceReference& reference, const surface::detail::VoxelSides* sides,
                      const ImproveOptions& options, ImproveReport& report, std::vector<char> frozen = {},
                      std::vector<char> seeds = {}, const std::map<Label, double>& volume_allowance_mm3 = {},
                      bool last = true, const Progress& progress = {});

/// improve_mesh() against a reference built before (tetrahedralize() builds it while TetGen runs); the report's
/// times leave its building out.
ImproveReport improve_mesh_against(TetMesh& mesh, const SurfaceReference& reference, const ImproveOptions& options,
                                   const Progress& progress = {});

} // namespace tissuemesh::volume::detail

// Many points located in a tet mesh by one pass over its tets, and the tets around chosen nodes: what the
// sources of a lead field need (thousands of dipoles on a mesh of millions of tets), without an index of the
// whole mesh.
#pragma once

#include <cstdint>
#include <vector>

#include "core/tet_mesh.h"

namespace tissuemesh::fem::detail {

/// Marks a point that no tet contains.
inline constexpr std::uint32_t outside_mesh = 0xffffffffu;

/// For each point (mm), the tet that contains it, or outside_mesh. A point on a shared face or edge goes to
/// the tet in which it is most interior (largest smallest barycentric coordinate; ties to the lower tet
/// index), as detail::locate_tet decides; 1e-9 of barycentric slack lets points on the outer boundary count
/// as inside. Parallel over the tets (OpenMP); the result does not depend on the thread count.
std::vector<std::uint32_t> locate_points(const TetMesh& mesh, const std::vector<Vec3>& points_mm);

/// The tets around each of `nodes`, in increasing order, found by one pass over the tets.
std::vector<std::vector<std::uint32_t>> tets_around(const TetMesh& mesh, const std::vector<std::uint32_t>& nodes);

} // namespace tissuemesh::fem::detail

// The outer boundary of a mesh the improver edits, kept from passing through itself.
//
// Tets keep interfaces inside the mesh from crossing: a face cannot pass another without turning a tet inside
// out. The outer boundary has tets on one side only, so a node sliding on it can carry its faces through a part
// of the boundary close by (a cleft of the liver sample, 0.2 mm wide, after decimation with contraction): no tet is
// inverted, yet tets overlap, and TetGen, given those faces to rebuild from (tm-refine), crashes or reports
// self-intersections.
#pragma once

#include <cstdint>
#include <vector>

#include "surface/detail/triangle_grid.h"

namespace tissuemesh::volume::detail {

class WorkMesh;

/// The faces of the outer boundary (constraint faces with one tet) in a uniform grid (surface's TriangleGrid). Entries
/// are added for every face an edit makes or moves and never removed; a query reads the faces as they are now, so
/// entries left behind by undone or later edits only cost a test.
class OuterBoundary {
public:
    /// The outer-boundary faces of `mesh` now; the grid spans its nodes, its cell twice the faces' mean edge.
    explicit OuterBoundary(const WorkMesh& mesh);

    /// Whether the outer-boundary faces the edits since `mark` added or moved meet no other outer-boundary face
    /// other than at the nodes and edges they share (exact predicates). Those faces join the grid either way.
    bool clear_since(const WorkMesh& mesh, std::size_t mark);

    std::size_t face_count() const { return faces_; }

private:
    /// Whether face f (on the outer boundary) meets another outer-boundary face.
    bool crosses(const WorkMesh& mesh, std::uint32_t f);

    std::size_t faces_ = 0;
    surface::detail::TriangleGrid grid_;
    std::vector<std::uint32_t> changed_, near_;
};

} // namespace tissuemesh::volume::detail

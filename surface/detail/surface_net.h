// The multi-label surface net of a label image, before smoothing: one vertex per grid cube whose corner
// labels differ, one polygon per grid edge whose two labels differ.
//
// How it stays a valid interface complex (closed and manifold per tissue, junctions shared, no
// intersections) with the connectivity rule of extract_interfaces(): the net is read as the dual of the
// same tetrahedralization of the voxel-centre grid that marching cubes uses (Kuhn's 6 tetrahedra per
// cube, or the priority rule's 12): a vertex per tetrahedron with mixed labels, a polygon per edge with
// mixed labels (the tetrahedra around it, in turn). A simplex has no ambiguous configuration, so this
// dual is manifold per tissue and keeps exactly the connectivity of the tetrahedralization. A cube's
// tetrahedra vertices are then merged into one vertex, the surface-nets vertex, where the cube's
// boundary allows it: every label's corners, and the other corners, connected on the cube's surface
// (its 12 edges and 6 chosen face diagonals), and no face crossed by two separate curves (four mixed
// edges with equal labels at the ends of the chosen diagonal). The merged vertex's neighbourhood is
// then a cone over one curve network on the cube's surface in which each tissue owns one disc, so the
// merge changes no topology. Cubes that fail the test (thin layers touching themselves through a face
// diagonal or a cube's centre, checkerboards) keep one vertex per mixed tetrahedron; a polygon with such
// vertices is fanned around a vertex at its edge's midpoint. On segmentations nearly every cube merges,
// so the net has about two triangles per voxel face between two labels (marching cubes: six to eight).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

#include "core/interface_complex.h"
#include "core/label_image.h"

namespace tissuemesh::surface::detail {

/// Where a vertex of the net may move while it is smoothed: an axis-aligned box in image index space
/// (low == high: the vertex stays).
struct VertexBox {
    Vec3 low{0, 0, 0};
    Vec3 high{0, 0, 0};
};

/// What a vertex of the net stands for.
enum class NetVertexKind : std::uint8_t {
    cube,        ///< a whole grid cube (its box: the cube)
    tetrahedron, ///< a mixed tetrahedron of a cube that could not be merged (fixed at its centroid)
    edge,        ///< the centre of a fanned polygon, at its edge's midpoint (fixed)
};

/// The surface net in image index space (voxel centres at integer indices).
struct SurfaceNet {
    std::vector<Vec3> positions;      ///< #V
    std::vector<VertexBox> boxes;     ///< #V: where each vertex may go
    std::vector<NetVertexKind> kinds; ///< #V
    std::vector<std::uint32_t> cells; ///< #V: index of the grid cube the vertex lies in (see cube_index)
    std::vector<Triangle> triangles;  ///< #T, oriented in index space (right-hand normal from `from` to `to`)
    std::vector<LabelPair> sides;     ///< #T
    std::array<std::size_t, 3> cube_grid{0, 0, 0}; ///< cubes per axis: image dims + 1
    std::size_t fallback_cubes = 0;                ///< mixed cubes kept as their tetrahedra
    std::size_t mixed_cubes = 0;                   ///< cubes whose corner labels differ
};

/// Cube (i, j, k) spans image indices [i - 1, i] x [j - 1, j] x [k - 1, k]; its index in SurfaceNet::cells.
inline std::uint32_t cube_index(const std::array<std::size_t, 3>& grid, std::size_t i, std::size_t j, std::size_t k)
{
    return static_cast<std::uint32_t>(i + grid[0] * (j + grid[1] * k));
}

/// Builds the net of `image` (labels mapped through `label_map`, outside the image `background`), with
/// the priority rule of ExtractOptions::priority. Sides follow extract_interfaces(): `from` the larger
/// label, the background always `to`.
/// @throws InputError when the net would have 2^31 vertices or more, or the image has 2^32 cubes or more
SurfaceNet build_surface_net(const LabelImage& image, const std::vector<Label>& label_map, Label background,
                             const std::map<Label, int>& priority);

} // namespace tissuemesh::surface::detail

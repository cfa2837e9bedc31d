// What the section views share: the plane through the mesh, its fit to the picture, and the polygon where
// the plane cuts a tet (with values interpolated along the cut edges).
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "core/tet_mesh.h"

namespace tissuemesh::render::detail {

using Point2 = std::array<double, 2>;

/// The plane axis = at, seen with the two other axes (u, v) in ascending order, v pointing up, the mesh's
/// extent in (u, v) fitted to 95% of the picture (or of its first `plot_width` px).
struct SectionFrame {
    int axis = 2, u = 0, v = 1;
    double at = 0;
    double scale = 1, mid_u = 0, mid_v = 0, centre_x = 0, centre_y = 0; ///< px per mm; screen centre of the fit

    Point2 to_screen(const Point2& p) const
    {
        return {centre_x + scale * (p[0] - mid_u), centre_y - scale * (p[1] - mid_v)};
    }
    /// The world point of the screen position (x, y) on the plane.
    Vec3 to_world(double x, double y) const;
};

/// The frame of `mesh` cut at its bounding box centre (`at_centre`) or at `position_mm`, in a picture of
/// `plot_width` x `height` px. `view` names the picture in messages ("section view").
/// @throws InputError when the mesh has no tet, the axis is not 0..2, or the plane misses the mesh
SectionFrame fit_section(const TetMesh& mesh, int axis, bool at_centre, double position_mm, double plot_width,
                         double height, const std::string& view);

/// The polygon where the frame's plane cuts tet `t` (3 or 4 points, convex, in order) in (u, v) mm, empty
/// when it does not cross; a vertex on the plane counts as above it. With `node_values` (one per vertex),
/// `values` gets the value at each point, linear along the cut edges.
void cut_tet(const TetMesh& mesh, std::size_t t, const SectionFrame& frame, std::vector<Point2>& points,
             const std::vector<double>* node_values = nullptr, std::vector<double>* values = nullptr);

/// The segments (in (u, v) mm) where the plane cuts the faces between tets of different tissues and the
/// faces on the mesh's boundary: the tissue outlines of the section.
std::vector<std::array<Point2, 2>> tissue_outlines(const TetMesh& mesh, const SectionFrame& frame);

} // namespace tissuemesh::render::detail

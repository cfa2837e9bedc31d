#include "volume/detail/outer_boundary.h"

#include <algorithm>

#include "surface/detail/cgal_intersections.h"
#include "surface/detail/triangle_grid.h"
#include "volume/detail/work_mesh.h"

namespace tissuemesh::volume::detail {
namespace {

surface::detail::Box3 box_of(const WorkMesh& mesh, const Triangle& c)
{
    return surface::detail::bounding_box({mesh.point(c[0]), mesh.point(c[1]), mesh.point(c[2])});
}

bool on_outer_boundary(const WorkMesh& mesh, std::uint32_t f)
{
    const ConstraintFace& face = mesh.face(f);
    return face.alive && mesh.holders(face.corners[0], face.corners[1], face.corners[2]) == 1;
}

} // namespace

OuterBoundary::OuterBoundary(const WorkMesh& mesh)
{
    std::vector<std::uint32_t> outer;
    double edges = 0;
    for (const std::uint32_t f : mesh.outer_faces_at_start()) {
        if (!mesh.face(f).alive) continue;
        outer.push_back(f);
        const Triangle& c = mesh.face(f).corners;
        for (int i = 0; i < 3; ++i) edges += distance(mesh.point(c[i]), mesh.point(c[(i + 1) % 3]));
    }
    faces_ = outer.size();
    if (outer.empty()) return;
    // Over the nodes' box: a node moved beyond it lands in the border cells, which only makes them fuller.
    surface::detail::Box3 bounds{mesh.point(0), mesh.point(0)};
    for (const Vec3& p : mesh.points()) bounds = surface::detail::box_union(bounds, {p, p});
    grid_ = surface::detail::TriangleGrid(bounds, std::max(2 * edges / (3.0 * static_cast<double>(outer.size())), 1e-6),
                                          mesh.face_slots());
    for (const std::uint32_t f : outer) grid_.insert(f, box_of(mesh, mesh.face(f).corners));
}

bool OuterBoundary::crosses(const WorkMesh& mesh, std::uint32_t f)
{
    const Triangle& c = mesh.face(f).corners;
    // A face with collinear corners belongs to a flat tet; the improver never makes one, so refuse it.
    if (surface::detail::are_collinear(mesh.point(c[0]), mesh.point(c[1]), mesh.point(c[2]))) return true;
    const surface::detail::Box3 box = box_of(mesh, c);
    grid_.query(box, near_);
    for (const std::uint32_t g : near_) {
        if (g == f || g >= mesh.face_slots()) continue;
        const Triangle& d = mesh.face(g).corners;
        if (!surface::detail::boxes_overlap(box, box_of(mesh, d)) || !on_outer_boundary(mesh, g)) continue;
        if (surface::detail::are_collinear(mesh.point(d[0]), mesh.point(d[1]), mesh.point(d[2]))) continue;
        if (surface::detail::triangles_intersect(mesh.points(), c, d)) return true;
    }
    return false;
}

bool OuterBoundary::clear_since(const WorkMesh& mesh, std::size_t mark)
{
    if (faces_ == 0) return true;
    mesh.faces_changed_since(mark, changed_);
    changed_.erase(
        std::remove_if(changed_.begin(), changed_.end(), [&](std::uint32_t f) { return !on_outer_boundary(mesh, f); }),
        changed_.end());
    for (const std::uint32_t f : changed_) grid_.insert(f, box_of(mesh, mesh.face(f).corners));
    return std::none_of(changed_.begin(), changed_.end(), [&](std::uint32_t f) { return crosses(mesh, f); });
}

} // namespace tissuemesh::volume::detail

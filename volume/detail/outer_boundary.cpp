#include "volume/detail/outer_boundary.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "surface/detail/cgal_intersections.h"
#include "volume/detail/work_mesh.h"

namespace tissuemesh::volume::detail {
namespace {

constexpr int cell_bits = 21;
constexpr std::int64_t cell_limit = (std::int64_t{1} << cell_bits) - 1;

std::array<Vec3, 2> box_of(const WorkMesh& mesh, const Triangle& c)
{
    Vec3 low = mesh.point(c[0]), high = low;
    for (int i = 1; i < 3; ++i)
        for (int k = 0; k < 3; ++k) {
            low[k] = std::min(low[k], mesh.point(c[i])[k]);
            high[k] = std::max(high[k], mesh.point(c[i])[k]);
        }
    return {low, high};
}

bool boxes_meet(const std::array<Vec3, 2>& a, const std::array<Vec3, 2>& b)
{
    for (int k = 0; k < 3; ++k)
        if (a[0][k] > b[1][k] || b[0][k] > a[1][k]) return false;
    return true;
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
    Vec3 low{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
             std::numeric_limits<double>::infinity()};
    for (const std::uint32_t f : mesh.outer_faces_at_start()) {
        if (!mesh.face(f).alive) continue;
        outer.push_back(f);
        const Triangle& c = mesh.face(f).corners;
        for (int i = 0; i < 3; ++i) {
            edges += distance(mesh.point(c[i]), mesh.point(c[(i + 1) % 3]));
            for (int k = 0; k < 3; ++k) low[k] = std::min(low[k], mesh.point(c[i])[k]);
        }
    }
    faces_ = outer.size();
    if (outer.empty()) return;
    cell_mm_ = std::max(2 * edges / (3.0 * static_cast<double>(outer.size())), 1e-6);
    // Nodes may move a little below the lowest corner; a margin of many cells keeps them on the grid.
    origin_ = low - Vec3{64 * cell_mm_, 64 * cell_mm_, 64 * cell_mm_};
    for (const std::uint32_t f : outer) insert(mesh, f);
}

template <class Visit>
void OuterBoundary::for_each_cell(const Vec3& low, const Vec3& high, Visit&& visit) const
{
    std::array<std::int64_t, 3> from{}, to{};
    for (int k = 0; k < 3; ++k) {
        from[k] = std::clamp(static_cast<std::int64_t>(std::floor((low[k] - origin_[k]) / cell_mm_)), std::int64_t{0},
                             cell_limit);
        to[k] = std::clamp(static_cast<std::int64_t>(std::floor((high[k] - origin_[k]) / cell_mm_)), std::int64_t{0},
                           cell_limit);
    }
    for (std::int64_t z = from[2]; z <= to[2]; ++z)
        for (std::int64_t y = from[1]; y <= to[1]; ++y)
            for (std::int64_t x = from[0]; x <= to[0]; ++x)
                visit(static_cast<Cell>(x) | static_cast<Cell>(y) << cell_bits | static_cast<Cell>(z) << 2 * cell_bits);
}

void OuterBoundary::insert(const WorkMesh& mesh, std::uint32_t f)
{
    const auto box = box_of(mesh, mesh.face(f).corners);
    for_each_cell(box[0], box[1], [&](Cell cell) {
        std::vector<std::uint32_t>& list = cells_[cell];
        if (list.empty() || list.back() != f) list.push_back(f);
    });
}

bool OuterBoundary::crosses(const WorkMesh& mesh, std::uint32_t f)
{
    const Triangle& c = mesh.face(f).corners;
    // A face with collinear corners belongs to a flat tet; the improver never makes one, so refuse it.
    if (surface::detail::are_collinear(mesh.point(c[0]), mesh.point(c[1]), mesh.point(c[2]))) return true;
    const auto box = box_of(mesh, c);
    if (seen_.size() < mesh.face_slots()) seen_.resize(mesh.face_slots(), 0);
    if (++query_ == 0) std::fill(seen_.begin(), seen_.end(), 0), query_ = 1;
    seen_[f] = query_;
    bool crossed = false;
    for_each_cell(box[0], box[1], [&](Cell cell) {
        if (crossed) return;
        const auto found = cells_.find(cell);
        if (found == cells_.end()) return;
        for (const std::uint32_t g : found->second) {
            if (g >= mesh.face_slots() || seen_[g] == query_) continue;
            seen_[g] = query_;
            const Triangle& d = mesh.face(g).corners;
            if (!boxes_meet(box, box_of(mesh, d)) || !on_outer_boundary(mesh, g)) continue;
            if (surface::detail::are_collinear(mesh.point(d[0]), mesh.point(d[1]), mesh.point(d[2]))) continue;
            if (surface::detail::triangles_intersect(mesh.points(), c, d)) {
                crossed = true;
                return;
            }
        }
    });
    return crossed;
}

bool OuterBoundary::clear_since(const WorkMesh& mesh, std::size_t mark)
{
    if (faces_ == 0) return true;
    mesh.faces_changed_since(mark, changed_);
    changed_.erase(
        std::remove_if(changed_.begin(), changed_.end(), [&](std::uint32_t f) { return !on_outer_boundary(mesh, f); }),
        changed_.end());
    for (const std::uint32_t f : changed_) insert(mesh, f);
    return std::none_of(changed_.begin(), changed_.end(), [&](std::uint32_t f) { return crosses(mesh, f); });
}

} // namespace tissuemesh::volume::detail

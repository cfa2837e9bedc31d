#include "surface/detail/surface_contacts.h"

#include <algorithm>
#include <set>

#include "surface/detail/cgal_intersections.h"
#include "surface/detail/triangle_grid.h"

namespace tissuemesh::surface::detail {
namespace {

bool shares_vertex(const Triangle& a, const Triangle& b)
{
    for (const std::uint32_t v : a)
        if (std::find(b.begin(), b.end(), v) != b.end()) return true;
    return false;
}

/// Triangles joined by an edge (a vertex of each) lie side by side where patches meet at a junction
/// curve: close by construction, not a contact to push apart.
bool joined_by_edge(const ComplexEditor& editor, const Triangle& a, const Triangle& b)
{
    for (const std::uint32_t v : a) {
        const std::vector<std::uint32_t> ring = editor.neighbours(v);
        for (const std::uint32_t w : b)
            if (std::binary_search(ring.begin(), ring.end(), w)) return true;
    }
    return false;
}

/// Smallest vertex-to-face distance between two triangles (the closest approach of near-parallel layers).
double vertex_face_distance(const TriangleCorners& a, const TriangleCorners& b)
{
    double d = 1e300;
    for (int k = 0; k < 3; ++k) {
        d = std::min(d, distance(a[k], closest_point_on_triangle(a[k], b)));
        d = std::min(d, distance(b[k], closest_point_on_triangle(b[k], a)));
    }
    return d;
}

} // namespace

bool same_patch(const LabelPair& a, const LabelPair& b)
{
    return std::minmax(a.from, a.to) == std::minmax(b.from, b.to);
}

Vec3 unit_normal(const TriangleCorners& c)
{
    const Vec3 n = cross(c[1] - c[0], c[2] - c[0]);
    const double length = norm(n);
    return length > 0 ? (1.0 / length) * n : Vec3{0, 0, 0};
}

bool degenerate(const ComplexEditor& editor, std::uint32_t t)
{
    const TriangleCorners c = editor.corners(t);
    return are_collinear(c[0], c[1], c[2]);
}

std::vector<Contact> find_contacts(const ComplexEditor& editor, double gap_mm)
{
    std::vector<Triangle> triangles(editor.triangle_slots());
    std::vector<std::uint32_t> alive;
    Box3 bounds{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
    for (std::uint32_t t = 0; t < triangles.size(); ++t) {
        if (!editor.triangle_alive(t) || degenerate(editor, t)) continue;
        triangles[t] = editor.triangle(t);
        alive.push_back(t);
        const Box3 box = bounding_box(editor.corners(t));
        for (int i = 0; i < 3; ++i)
            bounds.low[i] = std::min(bounds.low[i], box.low[i]), bounds.high[i] = std::max(bounds.high[i], box.high[i]);
    }
    std::vector<Contact> contacts;
    for (const auto& [a, b] : find_intersecting_pairs(editor.positions(), triangles, alive))
        contacts.push_back({a, b, true});
    if (gap_mm <= 0 || alive.empty()) return contacts;
    const std::set<std::pair<std::uint32_t, std::uint32_t>> crossing = [&] {
        std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
        for (const Contact& c : contacts) pairs.insert({c.a, c.b});
        return pairs;
    }();
    TriangleGrid grid(bounds, std::max(2 * gap_mm, editor.mean_edge_length()), editor.triangle_slots());
    for (const std::uint32_t t : alive) grid.insert(t, bounding_box(editor.corners(t)));
    std::vector<std::uint32_t> nearby;
    for (const std::uint32_t t : alive) {
        const TriangleCorners ct = editor.corners(t);
        const Box3 box = bounding_box(ct, gap_mm);
        grid.query(box, nearby);
        std::sort(nearby.begin(), nearby.end());
        for (const std::uint32_t u : nearby) {
            if (u <= t || same_patch(editor.side(t), editor.side(u)) ||
                shares_vertex(editor.triangle(t), editor.triangle(u)))
                continue;
            const TriangleCorners cu = editor.corners(u);
            if (!boxes_overlap(box, bounding_box(cu)) || crossing.contains({t, u})) continue;
            if (vertex_face_distance(ct, cu) < gap_mm &&
                !joined_by_edge(editor, editor.triangle(t), editor.triangle(u)))
                contacts.push_back({t, u, false});
        }
    }
    std::sort(contacts.begin(), contacts.end());
    return contacts;
}

} // namespace tissuemesh::surface::detail

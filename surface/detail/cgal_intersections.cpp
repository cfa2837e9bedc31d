// The only translation unit of the surface checker that includes CGAL: exact predicates
// (Exact_predicates_inexact_constructions_kernel), applied to the pairs whose bounding boxes overlap.
#include "surface/detail/cgal_intersections.h"

#include <algorithm>
#include <cmath>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include "surface/detail/box_index.h"
#include "surface/detail/plane_side.h"

namespace tissuemesh::surface::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Segment = Kernel::Segment_3;
using CgalTriangle = Kernel::Triangle_3;

Point to_point(const Vec3& v) { return Point(v[0], v[1], v[2]); }

TriangleCorners corners_of(const std::vector<Vec3>& vertices, const Triangle& t)
{
    return {vertices[t[0]], vertices[t[1]], vertices[t[2]]};
}

/// Rotates `t` so that the vertices it shares with `other` come first (one: it leads; two: the third is
/// last; none or three: no turn); returns how many it shares.
int shared_first(Triangle& t, const Triangle& other)
{
    const auto shared = [&](std::uint32_t v) { return v == other[0] || v == other[1] || v == other[2]; };
    const bool s0 = shared(t[0]), s1 = shared(t[1]), s2 = shared(t[2]);
    const int count = int{s0} + int{s1} + int{s2};
    // Rotations keep the orientation; only the order of the shared vertices matters below.
    const int turn = count == 1 ? (s0 ? 0 : s1 ? 1 : 2) : count == 2 ? (!s0 ? 1 : !s1 ? 2 : 0) : 0;
    if (turn != 0) t = {t[turn], t[(turn + 1) % 3], t[(turn + 2) % 3]};
    return count;
}

using Corners = std::array<Point, 3>;

CGAL::Orientation side(const Corners& t, const Point& p) { return CGAL::orientation(t[0], t[1], t[2], p); }

/// The axis to drop so that the projection of t's plane onto the other two axes is one-to-one (the
/// normal's largest component, confirmed exactly), or -1.
int projection_axis(const Corners& t)
{
    const Kernel::Vector_3 n = CGAL::cross_product(t[1] - t[0], t[2] - t[0]);
    const std::array<double, 3> size{std::abs(n.x()), std::abs(n.y()), std::abs(n.z())};
    const int axis = static_cast<int>(std::max_element(size.begin(), size.end()) - size.begin());
    const auto flat = [axis](const Point& p) { return Kernel::Point_2(p[(axis + 1) % 3], p[(axis + 2) % 3]); };
    return CGAL::collinear(flat(t[0]), flat(t[1]), flat(t[2])) ? -1 : axis;
}

using Point2 = Kernel::Point_2;
using Corners2 = std::array<Point2, 3>;

Point2 project(const Point& p, int axis) { return {p[(axis + 1) % 3], p[(axis + 2) % 3]}; }
Corners2 project(const Corners& t, int axis) { return {project(t[0], axis), project(t[1], axis), project(t[2], axis)}; }

// 2D tests on closed sets from orientation predicates only: CGAL's 2D do_intersect for triangles
// computes intersection points and, on degenerate input, falls back to rational arithmetic (the whole
// check of a 663 000-triangle voxel surface took 45 s with it, 3 s without).

/// Whether the closed segments pq and rs meet.
bool segments_meet(const Point2& p, const Point2& q, const Point2& r, const Point2& s)
{
    const int o1 = CGAL::orientation(p, q, r), o2 = CGAL::orientation(p, q, s);
    const int o3 = CGAL::orientation(r, s, p), o4 = CGAL::orientation(r, s, q);
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;
    // Otherwise they meet only if an end point lies on the other segment.
    return (o1 == 0 && CGAL::collinear_are_ordered_along_line(p, r, q)) ||
           (o2 == 0 && CGAL::collinear_are_ordered_along_line(p, s, q)) ||
           (o3 == 0 && CGAL::collinear_are_ordered_along_line(r, p, s)) ||
           (o4 == 0 && CGAL::collinear_are_ordered_along_line(r, q, s));
}

/// Whether p lies in the closed, non-degenerate triangle t.
bool in_triangle(const Corners2& t, const Point2& p)
{
    const int o0 = CGAL::orientation(t[0], t[1], p), o1 = CGAL::orientation(t[1], t[2], p),
              o2 = CGAL::orientation(t[2], t[0], p);
    return !((o0 < 0 || o1 < 0 || o2 < 0) && (o0 > 0 || o1 > 0 || o2 > 0));
}

bool segment_meets_triangle(const Point2& p, const Point2& q, const Corners2& t)
{
    return in_triangle(t, p) || in_triangle(t, q) || segments_meet(p, q, t[0], t[1]) ||
           segments_meet(p, q, t[1], t[2]) || segments_meet(p, q, t[2], t[0]);
}

/// Closed triangles meet when an edge of one meets the other (which covers containment).
bool triangles_meet(const Corners2& a, const Corners2& b)
{
    return segment_meets_triangle(a[0], a[1], b) || segment_meets_triangle(a[1], a[2], b) ||
           segment_meets_triangle(a[2], a[0], b) || in_triangle(a, b[0]);
}

/// Floating-point shortcuts in front of the exact tests: each returns true only when its answer "these
/// triangles do not meet improperly" is certain despite rounding (the determinants it trusts exceed
/// 1e-10 of the product of the lengths they multiply, far above the rounding of a few dozen operations),
/// and false when unsure, leaving the case to the exact predicates. On voxel-derived and smoothed
/// surfaces nearly every pair is decided here (measured: the exact fallback on coplanar terraces made a
/// local check cost about 100 us).
namespace filter {

constexpr double margin = 1e-10;

int side(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) { return certain_side(a, b, c, d); }

/// True when all of q's corners are certainly strictly on one side of p's plane.
bool off_plane(const std::array<Vec3, 3>& p, const std::array<Vec3, 3>& q, int first)
{
    const int s = side(p[0], p[1], p[2], q[first]);
    if (s == 0) return false;
    for (int k = first + 1; k < 3; ++k)
        if (side(p[0], p[1], p[2], q[k]) != s) return false;
    return true;
}

using Point2d = std::array<double, 2>;

/// Projection dropping the axis of the normal's largest component.
std::array<Point2d, 3> flatten(const std::array<Vec3, 3>& t, int axis)
{
    std::array<Point2d, 3> out{};
    for (int k = 0; k < 3; ++k) out[k] = {t[k][(axis + 1) % 3], t[k][(axis + 2) % 3]};
    return out;
}

/// True when the 2D convex sets `a` (na points) and `b` (nb points) are certainly apart: some edge
/// normal of either separates their projections with a margin.
bool separated(const Point2d* a, int na, const Point2d* b, int nb)
{
    const auto try_axes = [](const Point2d* p, int np, const Point2d* q, int nq) {
        for (int i = 0; i < np; ++i) {
            const Point2d& s = p[i];
            const Point2d& e = p[(i + 1) % np];
            const Point2d n{e[1] - s[1], s[0] - e[0]};
            const double length2 = n[0] * n[0] + n[1] * n[1];
            if (length2 == 0) continue;
            double pmin = 1e300, pmax = -1e300, qmin = 1e300, qmax = -1e300, reach2 = 0;
            const auto project = [&](const Point2d& x, double& low, double& high) {
                const double dx = x[0] - s[0], dy = x[1] - s[1];
                const double along = n[0] * dx + n[1] * dy;
                low = std::min(low, along), high = std::max(high, along);
                reach2 = std::max(reach2, dx * dx + dy * dy);
            };
            for (int k = 0; k < np; ++k) project(p[k], pmin, pmax);
            for (int k = 0; k < nq; ++k) project(q[k], qmin, qmax);
            const double tolerance = margin * std::sqrt(length2 * reach2);
            if (qmin > pmax + tolerance || pmin > qmax + tolerance) return true;
        }
        return false;
    };
    return (na > 1 && try_axes(a, na, b, nb)) || (nb > 1 && try_axes(b, nb, a, na));
}

int dominant_axis(const std::array<Vec3, 3>& t)
{
    const Vec3 n = cross(t[1] - t[0], t[2] - t[0]);
    const std::array<double, 3> size{std::abs(n[0]), std::abs(n[1]), std::abs(n[2])};
    return static_cast<int>(std::max_element(size.begin(), size.end()) - size.begin());
}

/// a and b rotated so that their `shared` common vertices come first (same order in both for an edge).
bool certainly_proper(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b, int shared)
{
    switch (shared) {
    case 0: {
        if (off_plane(a, b, 0) || off_plane(b, a, 0)) return true;
        const int axis = dominant_axis(a);
        const auto fa = flatten(a, axis), fb = flatten(b, axis);
        return separated(fa.data(), 3, fb.data(), 3); // disjoint shadows: disjoint triangles
    }
    case 1: {
        if (off_plane(a, b, 1) || off_plane(b, a, 1)) return true;
        // Otherwise improper exactly when a's far edge meets b or b's far edge meets a.
        const int axis = dominant_axis(a);
        const auto fa = flatten(a, axis), fb = flatten(b, axis);
        return separated(fa.data() + 1, 2, fb.data(), 3) && separated(fb.data() + 1, 2, fa.data(), 3);
    }
    case 2: {
        if (side(a[0], a[1], a[2], b[2]) != 0) return true;
        // Coplanar: proper when the third vertices lie on opposite sides of the shared edge.
        const int axis = dominant_axis(a);
        const auto fa = flatten(a, axis), fb = flatten(b, axis);
        const Point2d e{fa[1][0] - fa[0][0], fa[1][1] - fa[0][1]};
        const auto cross2 = [&](const Point2d& p) {
            const Point2d d{p[0] - fa[0][0], p[1] - fa[0][1]};
            const double c = e[0] * d[1] - e[1] * d[0];
            const double scale2 = (e[0] * e[0] + e[1] * e[1]) * (d[0] * d[0] + d[1] * d[1]);
            return c * c > margin * margin * scale2 ? (c > 0 ? 1 : -1) : 0;
        };
        const int sa = cross2(fa[2]), sb = cross2(fb[2]);
        return sa != 0 && sb != 0 && sa != sb;
    }
    default: return false;
    }
}

} // namespace filter

/// Whether two non-degenerate triangles meet anywhere besides the vertices and edge they share by index.
/// - no shared vertex: any contact is improper;
/// - one shared vertex v: if the triangles meet at a point p != v, they meet along the segment vp
///   (convexity), and the shorter of the two triangles' chords from v along that segment ends on the
///   edge opposite v; so the contact is improper exactly when an opposite edge meets the other triangle;
/// - a shared edge uw: triangles in different planes meet exactly in uw; coplanar ones overlap when
///   their third vertices lie on the same side of uw.
/// Coplanar pairs (common in voxel-derived surfaces) are decided in 2D after an exact one-to-one
/// projection: the 3D predicates would fall back to exact arithmetic on every zero orientation.
class PairTest {
public:
    PairTest(const std::vector<Vec3>& vertices, const std::vector<Triangle>& triangles)
        : vertices_(vertices), triangles_(triangles)
    {
    }

    bool intersects(std::uint32_t first, std::uint32_t second) const
    {
        return intersects(triangles_[first], triangles_[second]);
    }

    bool intersects(Triangle a, Triangle b) const
    {
        const int shared = shared_first(a, b);
        shared_first(b, a);
        if (filter::certainly_proper(plain(a), plain(b), shared)) return false;
        const Corners pa = corners(a), pb = corners(b);
        switch (shared) {
        case 0: return disjoint_meet(pa, pb);
        case 1: return vertex_sharing_meet(pa, pb);
        case 2:
            return CGAL::coplanar(pa[0], pa[1], pa[2], pb[2]) &&
                   CGAL::coplanar_orientation(pa[0], pa[1], pa[2], pb[2]) == CGAL::POSITIVE;
        default: return false; // same vertex set: a duplicate, reported by the caller
        }
    }

private:
    static bool disjoint_meet(const Corners& pa, const Corners& pb)
    {
        const CGAL::Orientation s0 = side(pa, pb[0]), s1 = side(pa, pb[1]), s2 = side(pa, pb[2]);
        if (s0 == s1 && s1 == s2) {
            if (s0 != CGAL::COPLANAR) return false; // b strictly on one side of a's plane
            if (const int axis = projection_axis(pa); axis >= 0)
                return triangles_meet(project(pa, axis), project(pb, axis));
        }
        return CGAL::do_intersect(CgalTriangle(pa[0], pa[1], pa[2]), CgalTriangle(pb[0], pb[1], pb[2]));
    }

    /// pa[0] and pb[0] are the shared vertex.
    static bool vertex_sharing_meet(const Corners& pa, const Corners& pb)
    {
        const CGAL::Orientation s1 = side(pa, pb[1]), s2 = side(pa, pb[2]);
        // b meets a's plane only at the shared vertex: nothing else can be common.
        if (s1 == s2 && s1 != CGAL::COPLANAR) return false;
        if (s1 == CGAL::COPLANAR && s2 == CGAL::COPLANAR)
            if (const int axis = projection_axis(pa); axis >= 0)
                return segment_meets_triangle(project(pa[1], axis), project(pa[2], axis), project(pb, axis)) ||
                       segment_meets_triangle(project(pb[1], axis), project(pb[2], axis), project(pa, axis));
        return CGAL::do_intersect(Segment(pa[1], pa[2]), CgalTriangle(pb[0], pb[1], pb[2])) ||
               CGAL::do_intersect(Segment(pb[1], pb[2]), CgalTriangle(pa[0], pa[1], pa[2]));
    }

    std::array<Vec3, 3> plain(const Triangle& t) const { return {vertices_[t[0]], vertices_[t[1]], vertices_[t[2]]}; }

    Corners corners(const Triangle& t) const
    {
        return {to_point(vertices_[t[0]]), to_point(vertices_[t[1]]), to_point(vertices_[t[2]])};
    }

    const std::vector<Vec3>& vertices_;
    const std::vector<Triangle>& triangles_;
};

Vec3 to_vec(const Point& p) { return {p.x(), p.y(), p.z()}; }

Vec3 centroid(const std::vector<Point>& points)
{
    Vec3 sum{0, 0, 0};
    for (const Point& p : points) sum = sum + to_vec(p);
    return (1.0 / static_cast<double>(points.size())) * sum;
}

} // namespace

bool are_collinear(const Vec3& a, const Vec3& b, const Vec3& c)
{
    return CGAL::collinear(to_point(a), to_point(b), to_point(c));
}

int orientation(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
    if (const int sure = certain_side(a, b, c, d); sure != 0) return sure;
    return static_cast<int>(CGAL::orientation(to_point(a), to_point(b), to_point(c), to_point(d)));
}

std::vector<TrianglePair> find_intersecting_pairs(const std::vector<Vec3>& vertices,
                                                  const std::vector<Triangle>& triangles,
                                                  const std::vector<std::uint32_t>& candidates)
{
    // Every pair whose boxes overlap is decided exactly; the boxes (single precision, rounded outward)
    // only select the pairs. Each triangle asks the index for the boxes its own box meets that come after
    // it (each pair once), on all threads; the pairs are sorted at the end, so the threads do not matter.
    std::vector<CompactBox> boxes(triangles.size());
    for (const std::uint32_t t : candidates) boxes[t] = compact(bounding_box(corners_of(vertices, triangles[t])));
    const BoxIndex index(boxes, candidates);
    const PairTest test(vertices, triangles);
    std::vector<TrianglePair> pairs;
    const auto count = static_cast<std::int64_t>(candidates.size());
#pragma omp parallel
    {
        std::vector<TrianglePair> found;
#pragma omp for schedule(dynamic, 4096) nowait
        for (std::int64_t n = 0; n < count; ++n) {
            const std::uint32_t t = candidates[static_cast<std::size_t>(n)];
            index.visit_later(t, bounding_box(corners_of(vertices, triangles[t])), [&](std::uint32_t u) {
                const std::uint32_t first = std::min(t, u), second = std::max(t, u);
                if (test.intersects(first, second)) found.emplace_back(first, second);
            });
        }
#pragma omp critical
        pairs.insert(pairs.end(), found.begin(), found.end());
    }
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

bool triangles_intersect(const std::vector<Vec3>& vertices, const Triangle& a, const Triangle& b)
{
    static const std::vector<Triangle> none;
    return PairTest(vertices, none).intersects(a, b);
}

Vec3 intersection_point(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b)
{
    const CgalTriangle ta(to_point(a[0]), to_point(a[1]), to_point(a[2]));
    const CgalTriangle tb(to_point(b[0]), to_point(b[1]), to_point(b[2]));
    const auto result = CGAL::intersection(ta, tb);
    if (result) {
        if (const Point* p = boost::get<Point>(&*result)) return to_vec(*p);
        if (const Segment* s = boost::get<Segment>(&*result)) return centroid({s->source(), s->target()});
        if (const CgalTriangle* t = boost::get<CgalTriangle>(&*result))
            return centroid({t->vertex(0), t->vertex(1), t->vertex(2)});
        if (const auto* polygon = boost::get<std::vector<Point>>(&*result))
            if (!polygon->empty()) return centroid(*polygon);
    }
    const Vec3 ca = (1.0 / 3.0) * (a[0] + a[1] + a[2]);
    const Vec3 cb = (1.0 / 3.0) * (b[0] + b[1] + b[2]);
    return 0.5 * (ca + cb);
}

} // namespace tissuemesh::surface::detail

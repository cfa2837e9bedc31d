// The only translation unit of the surface checker that includes CGAL: exact predicates
// (Exact_predicates_inexact_constructions_kernel) and box_intersection_d over triangle bounding boxes.
#include "surface/detail/cgal_intersections.h"

#include <algorithm>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

namespace tissuemesh::surface::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Segment = Kernel::Segment_3;
using CgalTriangle = Kernel::Triangle_3;

Point to_point(const Vec3& v) { return Point(v[0], v[1], v[2]); }

/// A triangle's bounding box whose id is the triangle index, so that reports do not depend on
/// allocation addresses or global counters.
class TriangleBox : public CGAL::Box_intersection_d::Box_d<double, 3, CGAL::Box_intersection_d::ID_NONE> {
public:
    using Base = CGAL::Box_intersection_d::Box_d<double, 3, CGAL::Box_intersection_d::ID_NONE>;
    using ID = std::size_t;
    TriangleBox(const CGAL::Bbox_3& box, std::uint32_t triangle) : Base(box), triangle_(triangle) {}
    ID id() const { return triangle_; }
    std::uint32_t triangle() const { return triangle_; }

private:
    std::uint32_t triangle_;
};

/// Rotates `t` so that the vertices it shares with `other` come first; returns how many it shares.
int shared_first(Triangle& t, const Triangle& other)
{
    const auto shared = [&](std::uint32_t v) { return std::find(other.begin(), other.end(), v) != other.end(); };
    int count = 0;
    for (const std::uint32_t v : t) count += shared(v) ? 1 : 0;
    // Rotations keep the orientation; only the order of the shared vertices matters below.
    for (int turn = 0; turn < 3; ++turn) {
        const bool leading = count == 1 ? shared(t[0]) : (count == 2 ? shared(t[0]) && shared(t[1]) : true);
        if (leading) break;
        std::rotate(t.begin(), t.begin() + 1, t.end());
    }
    return count;
}

/// Whether two non-degenerate triangles meet anywhere besides the vertices and edge they share by index.
/// - no shared vertex: any contact is improper;
/// - one shared vertex v: if the triangles meet at a point p != v, they meet along the segment vp
///   (convexity), and the shorter of the two triangles' chords from v along that segment ends on the
///   edge opposite v; so the contact is improper exactly when an opposite edge meets the other triangle;
/// - a shared edge uw: triangles in different planes meet exactly in uw; coplanar ones overlap when
///   their third vertices lie on the same side of uw.
class PairTest {
public:
    PairTest(const std::vector<Vec3>& vertices, const std::vector<Triangle>& triangles)
        : vertices_(vertices), triangles_(triangles)
    {
    }

    bool intersects(std::uint32_t first, std::uint32_t second) const
    {
        Triangle a = triangles_[first];
        Triangle b = triangles_[second];
        const int shared = shared_first(a, b);
        shared_first(b, a);
        switch (shared) {
        case 0: return CGAL::do_intersect(triangle(a), triangle(b));
        case 1:
            return CGAL::do_intersect(Segment(point(a[1]), point(a[2])), triangle(b)) ||
                   CGAL::do_intersect(Segment(point(b[1]), point(b[2])), triangle(a));
        case 2: {
            const Point& u = point(a[0]);
            const Point& w = point(a[1]);
            return CGAL::coplanar(u, w, point(a[2]), point(b[2])) &&
                   CGAL::coplanar_orientation(u, w, point(a[2]), point(b[2])) == CGAL::POSITIVE;
        }
        default: return false;  // same vertex set: a duplicate, reported by the caller
        }
    }

private:
    Point point(std::uint32_t v) const { return to_point(vertices_[v]); }
    CgalTriangle triangle(const Triangle& t) const { return CgalTriangle(point(t[0]), point(t[1]), point(t[2])); }

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

std::vector<TrianglePair> find_intersecting_pairs(const std::vector<Vec3>& vertices,
                                                  const std::vector<Triangle>& triangles,
                                                  const std::vector<std::uint32_t>& candidates)
{
    std::vector<TriangleBox> boxes;
    boxes.reserve(candidates.size());
    for (const std::uint32_t t : candidates) {
        const Triangle& tri = triangles[t];
        // Bounding boxes of double coordinates are exact; closed boxes keep touching triangles.
        boxes.emplace_back(to_point(vertices[tri[0]]).bbox() + to_point(vertices[tri[1]]).bbox() +
                               to_point(vertices[tri[2]]).bbox(),
                           t);
    }
    const PairTest test(vertices, triangles);
    std::vector<TrianglePair> pairs;
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const TriangleBox& a, const TriangleBox& b) {
        if (test.intersects(a.triangle(), b.triangle()))
            pairs.emplace_back(std::min(a.triangle(), b.triangle()), std::max(a.triangle(), b.triangle()));
    });
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    return pairs;
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

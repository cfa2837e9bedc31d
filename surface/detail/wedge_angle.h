// The opening of the wedge between two triangles that share exactly one vertex.
#pragma once

#include <cstdint>
#include <optional>

#include "core/interface_complex.h"
#include "surface/detail/triangle_distance.h"

namespace tissuemesh::surface::detail {

/// Two triangles that share one vertex (and no edge) meet there in a wedge. Its opening is the angle
/// between them as seen from the shared vertex: on a unit sphere around it, each triangle is the arc its
/// opposite edge subtends, and the opening is the spherical distance between the two arcs (radians turned
/// into degrees; 0 when the arcs cross, i.e. the triangles overlap along a segment from the vertex).
/// Why it matters: the gap between layers is measured only between triangles that share no vertex, so two
/// patches meeting at a junction vertex could otherwise lie on top of each other at any distance; TetGen
/// then makes flat tetrahedra between them (seen on the thin phantom's remeshed shell: an edge 1.5e-14 mm
/// above a triangle of the other side of the layer). Non-adjacent triangles of one flat fan are not a
/// thin wedge: their arcs lie on one great circle but apart along it.
/// `apex`: the shared vertex; (a1, a2) and (b1, b2): the other corners of each triangle.
double wedge_angle_deg(const Vec3& apex, const Vec3& a1, const Vec3& a2, const Vec3& b1, const Vec3& b2);

/// Whether the opening at the one vertex shared by `a` and `b` (corners `ca`, `cb`) is certainly at least
/// `limit_deg` (as wedge_between() computes it): a plane through the shared vertex has the rest of one
/// triangle on one side and the rest of the other on the other side (or the plane of one triangle has
/// the rest of the other on one side), every corner at an angle beyond the limit from it, with a margin far
/// above rounding. Then neither arc comes nearer than the limit to the plane, nor to the other arc. False
/// when unsure, or when the triangles do not share exactly one vertex. A few dot products instead of eight
/// arctangents: the editor asks this of every pair of neighbours sharing one vertex.
bool wedge_certainly_open(const Triangle& a, const TriangleCorners& ca, const Triangle& b, const TriangleCorners& cb,
                          double limit_deg);

/// The position (0..2) in `a` of the one vertex `a` and `b` share, or nothing when they share none or
/// more than one.
std::optional<int> single_shared_corner(const Triangle& a, const Triangle& b);

/// The opening (degrees) at the one vertex shared by triangles `a` and `b` with corners `ca` and `cb`
/// (in the triangles' vertex order), or nothing when they do not share exactly one vertex.
std::optional<double> wedge_between(const Triangle& a, const TriangleCorners& ca, const Triangle& b,
                                    const TriangleCorners& cb);

} // namespace tissuemesh::surface::detail

#include "volume/interface_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "core/error.h"
#include "volume/detail/surface_reference.h"

namespace tissuemesh::volume {

InterfaceDistance interface_distance(const TetMesh& mesh, const InterfaceComplex& surface)
{
    validate_indices(mesh, "mesh");
    if (mesh.faces.empty())
        throw InputError(
            "mesh: has no interface faces to compare with the surface (a .vtu stores none: use .msh or .mesh)");
    const detail::SurfaceReference reference(surface);
    std::set<std::pair<Label, Label>> pairs;
    for (const LabelPair& side : surface.sides) pairs.insert(std::minmax(side.from, side.to));
    // Searches reach over the whole complex: far nodes are measured, not skipped.
    Vec3 low = surface.vertices.empty() ? Vec3{0, 0, 0} : surface.vertices[0], high = low;
    for (const Vec3& v : surface.vertices)
        for (int a = 0; a < 3; ++a) low[a] = std::min(low[a], v[a]), high[a] = std::max(high[a], v[a]);
    const double reach = 2 * distance(low, high) + 1;

    InterfaceDistance result;
    std::vector<double> node_distance(mesh.vertices.size(), -1);
    double area_sum = 0, weighted = 0;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const LabelPair side = mesh.face_sides[f];
        if (!pairs.count(std::minmax(side.from, side.to))) {
            ++result.unmatched_faces;
            continue;
        }
        const Triangle& tri = mesh.faces[f];
        const Vec3 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]], &c = mesh.vertices[tri[2]];
        auto far = [&](const Vec3& p) { return reference.distance_to(p, side.from, side.to, false, reach); };
        for (const std::uint32_t v : tri) node_distance[v] = std::max(node_distance[v], far(mesh.vertices[v]));
        const double centre = far((1.0 / 3) * (a + b + c));
        const double area = 0.5 * norm(cross(b - a, c - a));
        area_sum += area, weighted += area * centre;
        result.max_face_mm =
            std::max({result.max_face_mm, centre, far(0.5 * (a + b)), far(0.5 * (b + c)), far(0.5 * (c + a))});
        ++result.faces;
    }
    result.mean_face_mm = area_sum > 0 ? weighted / area_sum : 0;
    double node_sum = 0;
    for (const double d : node_distance) {
        if (d < 0) continue;
        ++result.nodes, node_sum += d;
        result.max_node_mm = std::max(result.max_node_mm, d);
    }
    result.mean_node_mm = result.nodes > 0 ? node_sum / static_cast<double>(result.nodes) : 0;
    return result;
}

} // namespace tissuemesh::volume

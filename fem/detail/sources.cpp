#include "fem/detail/sources.h"

#include <algorithm>
#include <limits>
#include <map>

#include "core/error.h"
#include "fem/assemble.h"

namespace tissuemesh::fem::detail {

std::string electrode_label(const Electrode& electrode, std::size_t index)
{
    return electrode.name.empty() ? concat("electrode ", index + 1) : electrode.name;
}

ElectrodePatch electrode_patch(const TetMesh& mesh, const OuterBoundary& boundary, const Electrode& electrode,
                               std::size_t index)
{
    const auto inside = [&](std::uint32_t node) {
        return distance(mesh.vertices[node], electrode.centre_mm) <= electrode.radius_mm;
    };
    std::map<std::uint32_t, double> shares;
    for (std::uint32_t node : boundary.nodes)
        if (inside(node)) shares[node] = 0;
    ElectrodePatch patch;
    for (const Triangle& face : boundary.faces) {
        if (!inside(face[0]) || !inside(face[1]) || !inside(face[2])) continue;
        const Vec3& a = mesh.vertices[face[0]];
        const double area = 0.5 * norm(cross(mesh.vertices[face[1]] - a, mesh.vertices[face[2]] - a));
        for (std::uint32_t node : face) shares[node] += area / 3;
        patch.area_mm2 += area;
    }
    if (!(patch.area_mm2 > 0))
        throw InputError(concat(electrode_label(electrode, index), " at (", format_mm(electrode.centre_mm[0]), ", ",
                                format_mm(electrode.centre_mm[1]), ", ", format_mm(electrode.centre_mm[2]),
                                ") mm with radius ", format_mm(electrode.radius_mm), " mm covers ", shares.size(),
                                " boundary nodes and no whole boundary face; move it onto the surface or enlarge ",
                                "the radius"));
    for (const auto& [node, share] : shares) {
        patch.nodes.push_back(node);
        patch.node_area_mm2.push_back(share);
    }
    return patch;
}

std::size_t locate_tet(const TetMesh& mesh, const Vec3& point_mm, const std::string& what)
{
    // Barycentric coordinates from the P1 gradients: lambda_k(x) = 1_{k=0} + grad(phi_k) . (x - v0).
    std::size_t best = mesh.tet_count();
    double best_min = -std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
        const Tet& tet = mesh.tets[t];
        double low = std::numeric_limits<double>::infinity();
        double high = -low;
        for (int k = 0; k < 4; ++k) {
            const Vec3& v = mesh.vertices[tet[k]];
            low = std::min(low, v[0] + v[1] + v[2]);
            high = std::max(high, v[0] + v[1] + v[2]);
        }
        const double s = point_mm[0] + point_mm[1] + point_mm[2];
        if (s < low - 1e-9 || s > high + 1e-9) continue; // cheap rejection along (1,1,1)
        const P1Element element = p1_element(mesh, t);
        const Vec3 offset = metres_per_mm * (point_mm - mesh.vertices[tet[0]]);
        double smallest = 1;
        for (int k = 1; k < 4; ++k) smallest = std::min(smallest, dot(element.gradients[k], offset));
        double sum = 0;
        for (int k = 1; k < 4; ++k) sum += dot(element.gradients[k], offset);
        smallest = std::min(smallest, 1 - sum);
        if (smallest > best_min) {
            best_min = smallest;
            best = t;
        }
    }
    // 1e-9 in barycentric units: points on a face shared with no other tet still count as inside.
    if (best == mesh.tet_count() || best_min < -1e-9)
        throw InputError(concat(what, " at (", format_mm(point_mm[0]), ", ", format_mm(point_mm[1]), ", ",
                                format_mm(point_mm[2]), ") mm lies outside the mesh; give a position inside it"));
    return best;
}

void add_dipole_load(const TetMesh& mesh, const Dipole& dipole, std::size_t index, Eigen::VectorXd& rhs)
{
    const std::size_t t = locate_tet(mesh, dipole.position_mm, concat("dipole ", index + 1));
    const P1Element element = p1_element(mesh, t);
    for (int k = 0; k < 4; ++k) rhs[mesh.tets[t][k]] += dot(dipole.moment_am, element.gradients[k]);
}

} // namespace tissuemesh::fem::detail

#include "fem/outer_boundary.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "core/error.h"
#include "core/tet_adjacency.h"
#include "core/tet_shape.h"

namespace tissuemesh::fem {
namespace {

struct BoundaryFace {
    Triangle sorted;   ///< its vertices in increasing order: the key that pairs it with a neighbour's face
    Triangle oriented; ///< as its tet has it (outwards)
};

BoundaryFace face_of(const Tet& tet, int k)
{
    BoundaryFace face{{}, {tet[tet_faces[k][0]], tet[tet_faces[k][1]], tet[tet_faces[k][2]]}};
    face.sorted = face.oriented;
    std::sort(face.sorted.begin(), face.sorted.end());
    return face;
}

// The boundary from its faces in any order: sorted by their vertex triples, nodes listed once.
OuterBoundary boundary_from(std::vector<BoundaryFace> faces)
{
    std::sort(faces.begin(), faces.end(),
              [](const BoundaryFace& a, const BoundaryFace& b) { return a.sorted < b.sorted; });
    OuterBoundary boundary;
    for (const BoundaryFace& face : faces) {
        boundary.faces.push_back(face.oriented);
        boundary.nodes.insert(boundary.nodes.end(), face.oriented.begin(), face.oriented.end());
    }
    std::sort(boundary.nodes.begin(), boundary.nodes.end());
    boundary.nodes.erase(std::unique(boundary.nodes.begin(), boundary.nodes.end()), boundary.nodes.end());
    return boundary;
}

} // namespace

OuterBoundary outer_boundary(const TetMesh& mesh)
{
    if (mesh.tets.empty()) return {};
    validate_indices(mesh, "mesh");
    const TetAdjacency adjacency(mesh.tets, mesh.vertex_count());
    std::vector<BoundaryFace> faces;
    for (std::size_t t = 0; t < mesh.tet_count(); ++t)
        for (int k = 0; k < 4; ++k)
            if (adjacency.across(t, k) == no_tet) faces.push_back(face_of(mesh.tets[t], k));
    return boundary_from(std::move(faces));
}

// Both tets of an inner face that has a node in the ball hold that node, so pairing the faces of the tets
// around the ball's nodes finds every such face twice: what is found once is on the boundary.
OuterBoundary outer_boundary_near(const TetMesh& mesh, const Vec3& centre_mm, double radius_mm)
{
    if (mesh.tets.empty()) return {};
    validate_indices(mesh, "mesh");
    if (!(radius_mm >= 0) || !std::isfinite(radius_mm) || !std::isfinite(norm(centre_mm)))
        throw InputError(concat("boundary near (", centre_mm[0], ", ", centre_mm[1], ", ", centre_mm[2],
                                ") mm: radius ", radius_mm, " mm; give a finite centre and a finite radius >= 0"));
    const auto count = static_cast<std::int64_t>(mesh.vertex_count());
    std::vector<char> inside(mesh.vertex_count());
#pragma omp parallel for schedule(static)
    for (std::int64_t v = 0; v < count; ++v)
        inside[static_cast<std::size_t>(v)] =
            distance(mesh.vertices[static_cast<std::size_t>(v)], centre_mm) <= radius_mm;
    std::vector<BoundaryFace> faces;
    for (const Tet& tet : mesh.tets) {
        if (!inside[tet[0]] && !inside[tet[1]] && !inside[tet[2]] && !inside[tet[3]]) continue;
        for (int k = 0; k < 4; ++k) {
            const BoundaryFace face = face_of(tet, k);
            if (inside[face.sorted[0]] || inside[face.sorted[1]] || inside[face.sorted[2]]) faces.push_back(face);
        }
    }
    std::sort(faces.begin(), faces.end(),
              [](const BoundaryFace& a, const BoundaryFace& b) { return a.sorted < b.sorted; });
    std::vector<BoundaryFace> once;
    for (std::size_t i = 0; i < faces.size();) {
        std::size_t j = i + 1;
        while (j < faces.size() && faces[j].sorted == faces[i].sorted) ++j;
        if (j == i + 1) once.push_back(faces[i]);
        i = j;
    }
    OuterBoundary boundary = boundary_from(std::move(once));
    std::erase_if(boundary.nodes, [&](std::uint32_t node) { return !inside[node]; });
    return boundary;
}

} // namespace tissuemesh::fem

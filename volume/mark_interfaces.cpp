#include "volume/mark_interfaces.h"

#include "core/error.h"
#include "core/tet_adjacency.h"
#include "volume/detail/face_map.h"

namespace tissuemesh::volume {

void mark_interfaces(TetMesh& mesh, Label background)
{
    validate_indices(mesh, "mesh");
    const TetAdjacency adjacency(mesh.tets, mesh.vertices.size());
    std::vector<Triangle> marked;
    std::vector<LabelPair> sides;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& tet = mesh.tets[t];
        for (int k = 0; k < 4; ++k) {
            const auto& local = detail::local_faces[k];
            // local_faces' right-hand normal points into a positive tet (opposite vertex i lies in front of
            // it, whatever face_map.h's comment says): swap two vertices for the outward face.
            const Triangle outward{tet[static_cast<std::size_t>(local[0])], tet[static_cast<std::size_t>(local[2])],
                                   tet[static_cast<std::size_t>(local[1])]};
            const std::uint32_t holders = adjacency.holders(t, k);
            if (holders > 2)
                throw InputError(concat("mesh: a face of tetrahedron ", t, " is shared by ", holders,
                                        " tetrahedra; the mesh is not conforming (run tm-check-mesh)"));
            const Label mine = mesh.tet_labels[t];
            if (holders == 1) {
                marked.push_back(outward), sides.push_back({mine, background});
                continue;
            }
            const std::size_t other = adjacency.across(t, k);
            const Label theirs = mesh.tet_labels[other];
            if (theirs == mine || other < t) continue; // no interface, or emitted with the other tet
            const bool mine_is_from = theirs == background || (mine != background && mine > theirs);
            if (mine_is_from) marked.push_back(outward), sides.push_back({mine, theirs});
            else marked.push_back({outward[0], outward[2], outward[1]}), sides.push_back({theirs, mine});
        }
    }
    mesh.faces = std::move(marked);
    mesh.face_sides = std::move(sides);
}

} // namespace tissuemesh::volume

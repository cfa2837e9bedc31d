#include "fem/outer_boundary.h"

#include <algorithm>

#include "fem/detail/incidence.h"

namespace tissuemesh::fem {

OuterBoundary outer_boundary(const TetMesh& mesh)
{
    if (mesh.tets.empty()) return {};
    validate_indices(mesh, "mesh");
    const std::vector<std::uint32_t> neighbours = detail::face_neighbours(mesh);
    struct Entry {
        Triangle sorted;
        Triangle oriented;
    };
    std::vector<Entry> entries;
    for (std::size_t t = 0; t < mesh.tet_count(); ++t)
        for (int k = 0; k < 4; ++k) {
            if (neighbours[4 * t + static_cast<std::size_t>(k)] != detail::no_tet) continue;
            const Tet& tet = mesh.tets[t];
            Entry entry{{}, {tet[detail::face_vertices[k][0]], tet[detail::face_vertices[k][1]],
                             tet[detail::face_vertices[k][2]]}};
            entry.sorted = entry.oriented;
            std::sort(entry.sorted.begin(), entry.sorted.end());
            entries.push_back(entry);
        }
    std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.sorted < b.sorted; });
    OuterBoundary boundary;
    for (const Entry& entry : entries) {
        boundary.faces.push_back(entry.oriented);
        boundary.nodes.insert(boundary.nodes.end(), entry.oriented.begin(), entry.oriented.end());
    }
    std::sort(boundary.nodes.begin(), boundary.nodes.end());
    boundary.nodes.erase(std::unique(boundary.nodes.begin(), boundary.nodes.end()), boundary.nodes.end());
    return boundary;
}

} // namespace tissuemesh::fem

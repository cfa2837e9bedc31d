#include "fem/outer_boundary.h"

#include <algorithm>

namespace tissuemesh::fem {

OuterBoundary outer_boundary(const TetMesh& mesh)
{
    // Faces opposite each vertex, oriented so that the right-hand normal points out of a positive tet.
    static constexpr int opposite[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
    struct Entry {
        Triangle sorted;
        Triangle oriented;
    };
    std::vector<Entry> entries;
    entries.reserve(4 * mesh.tet_count());
    for (const Tet& tet : mesh.tets)
        for (const auto& face : opposite) {
            Entry entry{{}, {tet[face[0]], tet[face[1]], tet[face[2]]}};
            entry.sorted = entry.oriented;
            std::sort(entry.sorted.begin(), entry.sorted.end());
            entries.push_back(entry);
        }
    std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.sorted < b.sorted; });
    OuterBoundary boundary;
    for (std::size_t i = 0; i < entries.size();) {
        std::size_t j = i + 1;
        while (j < entries.size() && entries[j].sorted == entries[i].sorted) ++j;
        if (j - i == 1) {
            boundary.faces.push_back(entries[i].oriented);
            boundary.nodes.insert(boundary.nodes.end(), entries[i].oriented.begin(), entries[i].oriented.end());
        }
        i = j;
    }
    std::sort(boundary.nodes.begin(), boundary.nodes.end());
    boundary.nodes.erase(std::unique(boundary.nodes.begin(), boundary.nodes.end()), boundary.nodes.end());
    return boundary;
}

} // namespace tissuemesh::fem

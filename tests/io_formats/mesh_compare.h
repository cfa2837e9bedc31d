// Comparing tet meshes independent of element order (formats may group elements by tissue).
#pragma once

#include <algorithm>
#include <tuple>
#include <vector>

#include "core/tet_mesh.h"

namespace tissuemesh::testing {

/// Each tet as (label, its vertex indices rotated so the smallest comes first, orientation kept), sorted.
inline std::vector<std::tuple<Label, std::array<std::uint32_t, 4>>> tet_set(const TetMesh& mesh)
{
    std::vector<std::tuple<Label, std::array<std::uint32_t, 4>>> set;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        Tet tet = mesh.tets[t];
        // Even permutations keep the orientation: bring the smallest index to the front with one.
        const auto smallest = static_cast<std::size_t>(std::min_element(tet.begin(), tet.end()) - tet.begin());
        if (smallest == 1) tet = {tet[1], tet[0], tet[3], tet[2]};
        if (smallest == 2) tet = {tet[2], tet[3], tet[0], tet[1]};
        if (smallest == 3) tet = {tet[3], tet[2], tet[1], tet[0]};
        // Then the other three in their cyclic order starting from the smallest of them.
        std::array<std::uint32_t, 3> rest{tet[1], tet[2], tet[3]};
        std::rotate(rest.begin(), std::min_element(rest.begin(), rest.end()), rest.end());
        set.emplace_back(mesh.tet_labels[t], std::array<std::uint32_t, 4>{tet[0], rest[0], rest[1], rest[2]});
    }
    std::sort(set.begin(), set.end());
    return set;
}

/// Each face as (from, to, its vertices rotated to start at the smallest), sorted.
inline std::vector<std::tuple<Label, Label, Triangle>> face_set(const TetMesh& mesh)
{
    std::vector<std::tuple<Label, Label, Triangle>> set;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        Triangle tri = mesh.faces[f];
        std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
        set.emplace_back(mesh.face_sides[f].from, mesh.face_sides[f].to, tri);
    }
    std::sort(set.begin(), set.end());
    return set;
}

} // namespace tissuemesh::testing

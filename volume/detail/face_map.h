// Triangular faces keyed by their vertex set, for the maps of faces that change as a mesh is edited (the
// face adjacency of a whole mesh is core/tet_adjacency.h), and the local faces turned inwards.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "core/tet_shape.h"

namespace tissuemesh::volume::detail {

struct FaceKey {
    std::array<std::uint32_t, 3> v; ///< ascending vertex indices
    bool operator==(const FaceKey&) const = default;
};

struct FaceKeyHash {
    std::size_t operator()(const FaceKey& key) const
    {
        std::uint64_t h = key.v[0];
        h = h * 0x9E3779B97F4A7C15ull ^ key.v[1];
        h = h * 0x9E3779B97F4A7C15ull ^ key.v[2];
        return static_cast<std::size_t>(h ^ (h >> 29));
    }
};

inline FaceKey face_key(std::uint32_t a, std::uint32_t b, std::uint32_t c)
{
    std::array<std::uint32_t, 3> v{a, b, c};
    std::sort(v.begin(), v.end());
    return {v};
}

/// Local faces of a tet, opposite vertex i, ordered so that for a positive tet the face normal (right-hand
/// rule) points into the tet, towards vertex i: core's tet_faces, each face turned over.
inline constexpr int local_faces[4][3] = {{tet_faces[0][0], tet_faces[0][2], tet_faces[0][1]},
                                          {tet_faces[1][0], tet_faces[1][2], tet_faces[1][1]},
                                          {tet_faces[2][0], tet_faces[2][2], tet_faces[2][1]},
                                          {tet_faces[3][0], tet_faces[3][2], tet_faces[3][1]}};

} // namespace tissuemesh::volume::detail

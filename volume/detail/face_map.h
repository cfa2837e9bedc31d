// Triangular faces of a tet mesh keyed by their vertex set, and the tets on each side.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/tet_shape.h"

namespace tissuemesh::volume::detail {

struct FaceKey {
    std::array<std::uint32_t, 3> v;  ///< ascending vertex indices
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

/// The tets using a face: the first two, and how many there are (more than two: non-conforming).
struct FaceUse {
    std::int64_t tets[2] = {-1, -1};
    int count = 0;
};

/// Local faces of a tet, opposite vertex i, ordered so that for a positive tet the face normal (right-hand
/// rule) points into the tet, towards vertex i: core's tet_faces, each face turned over.
inline constexpr int local_faces[4][3] = {{tet_faces[0][0], tet_faces[0][2], tet_faces[0][1]},
                                          {tet_faces[1][0], tet_faces[1][2], tet_faces[1][1]},
                                          {tet_faces[2][0], tet_faces[2][2], tet_faces[2][1]},
                                          {tet_faces[3][0], tet_faces[3][2], tet_faces[3][1]}};

/// Maps every face of `tets` (any 4-index type) to the tets that use it.
template <typename TetList>
std::unordered_map<FaceKey, FaceUse, FaceKeyHash> map_faces(const TetList& tets)
{
    std::unordered_map<FaceKey, FaceUse, FaceKeyHash> faces;
    faces.reserve(2 * tets.size() + 16);
    for (std::size_t t = 0; t < tets.size(); ++t)
        for (const auto& local : local_faces) {
            FaceUse& use = faces[face_key(static_cast<std::uint32_t>(tets[t][local[0]]), static_cast<std::uint32_t>(tets[t][local[1]]),
                                          static_cast<std::uint32_t>(tets[t][local[2]]))];
            if (use.count < 2) use.tets[use.count] = static_cast<std::int64_t>(t);
            ++use.count;
        }
    return faces;
}

} // namespace tissuemesh::volume::detail

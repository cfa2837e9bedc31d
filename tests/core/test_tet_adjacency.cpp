// core/tet_adjacency.h, the one face adjacency of the project (issue 32: "tet face adjacency twice", in
// volume/detail/face_map.h and fem/detail/incidence.h): invariants on a structured mesh, and the faces a
// non-conforming mesh shares three times.
#include <gtest/gtest.h>

#include <set>

#include "core/tet_adjacency.h"
#include "core/tet_shape.h"

namespace tissuemesh {
namespace {

/// An n^3 block of unit cubes, each cut into the 6 Kuhn tets (corner 0 to corner 7): conforming.
std::vector<Tet> kuhn_block(std::uint32_t n)
{
    const auto node = [n](std::uint32_t i, std::uint32_t j, std::uint32_t k) {
        return (k * (n + 1) + j) * (n + 1) + i;
    };
    const int chains[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
    std::vector<Tet> tets;
    for (std::uint32_t k = 0; k < n; ++k)
        for (std::uint32_t j = 0; j < n; ++j)
            for (std::uint32_t i = 0; i < n; ++i)
                for (const auto& chain : chains) {
                    Tet tet{};
                    for (int c = 0; c < 4; ++c)
                        tet[c] = node(i + (chain[c] & 1), j + (chain[c] >> 1 & 1), k + (chain[c] >> 2 & 1));
                    tets.push_back(tet);
                }
    return tets;
}

TEST(TetFaceAdjacencyTwice, KuhnBlockPairsEveryInnerFaceBothWaysAndLeavesTheBoundaryOpen)
{
    const std::uint32_t n = 3;
    const std::vector<Tet> tets = kuhn_block(n);
    const TetAdjacency adjacency(tets, (n + 1) * (n + 1) * (n + 1));
    std::size_t boundary = 0;
    for (std::size_t t = 0; t < tets.size(); ++t)
        for (int k = 0; k < 4; ++k) {
            const std::uint32_t other = adjacency.across(t, k);
            if (other == no_tet) {
                ++boundary;
                EXPECT_EQ(adjacency.holders(t, k), 1u);
                continue;
            }
            EXPECT_EQ(adjacency.holders(t, k), 2u);
            // The tet across holds the same three vertices, and sees t across that face.
            const std::set<std::uint32_t> face{tets[t][tet_faces[k][0]], tets[t][tet_faces[k][1]],
                                               tets[t][tet_faces[k][2]]};
            int back = -1;
            for (int m = 0; m < 4; ++m)
                if (std::set<std::uint32_t>{tets[other][tet_faces[m][0]], tets[other][tet_faces[m][1]],
                                            tets[other][tet_faces[m][2]]} == face)
                    back = m;
            ASSERT_GE(back, 0) << "tet " << t << " face " << k;
            EXPECT_EQ(adjacency.across(other, back), t);
        }
    EXPECT_EQ(boundary, 6u * 2u * n * n); // each of the block's 6 sides: n^2 squares of 2 triangles
    const std::vector<TetAdjacency::Face> faces = adjacency.faces();
    EXPECT_EQ(faces.size(), (4 * tets.size() + boundary) / 2);
    for (std::size_t f = 1; f < faces.size(); ++f) EXPECT_LT(faces[f - 1].vertices, faces[f].vertices);
}

TEST(TetFaceAdjacencyTwice, FindAndIntTetsAgreeWithTheFaceList)
{
    const std::vector<std::array<int, 4>> tets{{0, 1, 2, 3}, {1, 2, 3, 4}};
    const TetAdjacency adjacency(tets, 5);
    const TetAdjacency::Face shared = adjacency.find(3, 1, 2);
    EXPECT_EQ(shared.holders, 2u);
    EXPECT_EQ(shared.tets, (std::array<std::uint32_t, 2>{0, 1}));
    EXPECT_EQ(shared.vertices, (std::array<std::uint32_t, 3>{1, 2, 3}));
    EXPECT_EQ(adjacency.find(0, 1, 2).holders, 1u);
    EXPECT_EQ(adjacency.find(0, 1, 2).tets[1], no_tet);
    EXPECT_EQ(adjacency.find(0, 1, 4).holders, 0u);
    EXPECT_EQ(adjacency.find(7, 8, 9).holders, 0u) << "vertices beyond the mesh are in no face";
    EXPECT_EQ(adjacency.faces().size(), 7u);
    EXPECT_EQ(adjacency.across(0, 0), 1u); // face 0 of tet 0 is opposite corner 0: {1, 2, 3}
    EXPECT_EQ(adjacency.across(1, 3), 0u); // face 3 of tet 1 is opposite corner 3 (vertex 4): {1, 2, 3}
}

TEST(TetFaceAdjacencyTwice, AFaceOfThreeTetsIsCountedAndOnlyItsFirstTwoArePaired)
{
    const std::vector<Tet> tets{{0, 1, 2, 3}, {1, 2, 3, 4}, {1, 2, 3, 5}};
    const TetAdjacency adjacency(tets, 6);
    EXPECT_EQ(adjacency.holders(2, 3), 3u);
    EXPECT_EQ(adjacency.find(1, 2, 3).holders, 3u);
    EXPECT_EQ(adjacency.across(0, 0), 1u);
    EXPECT_EQ(adjacency.across(1, 3), 0u);
    EXPECT_EQ(adjacency.across(2, 3), no_tet);
}

TEST(TetFaceAdjacencyTwice, FacesPerVertexAreTheFaceListWhateverTheCornerOrder)
{
    // The same block with each tet's corners in one of many orders: the faces' smallest vertices are counted
    // from the tet's two smallest, which these orders put in every position.
    const std::uint32_t n = 3, vertices = (n + 1) * (n + 1) * (n + 1);
    const std::vector<Tet> tets = kuhn_block(n);
    std::vector<Tet> turned = tets;
    const int orders[6][4] = {{3, 2, 1, 0}, {1, 3, 0, 2}, {2, 0, 3, 1}, {0, 3, 1, 2}, {3, 0, 2, 1}, {2, 1, 0, 3}};
    for (std::size_t t = 0; t < tets.size(); ++t)
        for (int c = 0; c < 4; ++c) turned[t][c] = tets[t][orders[t % 6][c]];
    const TetAdjacency plain(tets, vertices), adjacency(turned, vertices);
    const std::vector<TetAdjacency::Face> faces = plain.faces();
    std::vector<TetAdjacency::Face> visited;
    std::set<std::size_t> ids;
    ASSERT_EQ(adjacency.vertex_count(), vertices);
    for (std::uint32_t v = 0; v < adjacency.vertex_count(); ++v)
        adjacency.for_each_face_at(v, [&](const TetAdjacency::Face& face) {
            EXPECT_EQ(face.vertices[0], v);
            EXPECT_LT(face.id, adjacency.id_count());
            EXPECT_EQ(adjacency.find(face.vertices[2], face.vertices[0], face.vertices[1]).id, face.id);
            ids.insert(face.id);
            visited.push_back(face);
        });
    ASSERT_EQ(visited.size(), faces.size());
    EXPECT_EQ(ids.size(), faces.size()) << "one id per face";
    for (std::size_t f = 0; f < faces.size(); ++f) {
        EXPECT_EQ(visited[f].vertices, faces[f].vertices);
        EXPECT_EQ(visited[f].holders, faces[f].holders);
        EXPECT_EQ(visited[f].tets, faces[f].tets);
    }
    for (std::size_t t = 0; t < tets.size(); ++t)
        for (int k = 0; k < 4; ++k) {
            // Face k of the turned tet is opposite its corner k, which is corner orders[t % 6][k] of the plain one.
            const int plain_k = orders[t % 6][k];
            EXPECT_EQ(adjacency.across(t, k), plain.across(t, plain_k)) << "tet " << t << " face " << k;
            EXPECT_EQ(adjacency.holders(t, k), plain.holders(t, plain_k));
        }
}

} // namespace
} // namespace tissuemesh

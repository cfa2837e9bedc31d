#include <gtest/gtest.h>

#include "volume/detail/outer_boundary.h"
#include "volume/detail/work_mesh.h"

namespace tissuemesh::volume::detail {
namespace {

/// Two tets with no node in common, apart: eight faces of the outer boundary.
TetMesh two_tets()
{
    TetMesh mesh;
    mesh.vertices = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}, {3, 3, 3}, {5, 3, 3}, {3, 5, 3}, {3, 3, 5}};
    mesh.tets = {{0, 1, 2, 3}, {4, 5, 6, 7}};
    mesh.tet_labels = {1, 1};
    return mesh;
}

TEST(OuterBoundary, ANodeMovedThroughAnotherPartOfTheBoundaryIsCaught)
{
    WorkMesh work(two_tets());
    OuterBoundary outer(work);
    EXPECT_EQ(outer.face_count(), 8u);

    // Into the first tet: the second stays positive (its node moves away from its opposite face), no tet is
    // inverted, but its faces now pass through the first tet's.
    std::size_t mark = work.mark();
    work.move_node(4, {0.3, 0.3, 0.3});
    ASSERT_GT(work.quality(1), 0);
    EXPECT_FALSE(outer.clear_since(work, mark));
    work.rollback(mark);
    EXPECT_TRUE(outer.clear_since(work, mark)) << "nothing changed since the mark";

    // Closer, still clear of the first tet: allowed; then through it from there, caught again (the grid knows the
    // faces where they are now).
    mark = work.mark();
    work.move_node(4, {1.2, 1.2, 1.2});
    EXPECT_TRUE(outer.clear_since(work, mark));
    work.commit();
    mark = work.mark();
    work.move_node(4, {0.5, 0.5, 0.5});
    EXPECT_FALSE(outer.clear_since(work, mark));
    work.rollback(mark);

    // A node of the first tet moved into the second (its node 4 now at (1.2, 1.2, 1.2)), the first tet positive.
    mark = work.mark();
    work.move_node(3, {1.7, 1.5, 1.6});
    ASSERT_GT(work.quality(0), 0);
    EXPECT_FALSE(outer.clear_since(work, mark));
    work.rollback(mark);
}

TEST(OuterBoundary, FacesThatShareANodeOnlyTouch)
{
    // Two tets sharing node 3 meet only there; moving the second's other nodes about that node stays clear.
    TetMesh mesh;
    mesh.vertices = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}, {2, 0, 4}, {0, 2, 4}, {0, 0, 4}};
    mesh.tets = {{0, 1, 2, 3}, {3, 4, 5, 6}};
    mesh.tet_labels = {1, 1};
    WorkMesh work(mesh);
    OuterBoundary outer(work);
    EXPECT_EQ(outer.face_count(), 8u);
    const std::size_t mark = work.mark();
    work.move_node(4, {3, 0, 3});
    EXPECT_TRUE(outer.clear_since(work, mark));
    work.rollback(mark);
    // Pushed into the first tet (x + y + z < 2), the tet still positive: its edge to node 5 leaves the first tet
    // through a face.
    work.move_node(4, {1.0, 0.1, 0.3});
    ASSERT_GT(work.quality(1), 0);
    EXPECT_FALSE(outer.clear_since(work, mark));
}

} // namespace
} // namespace tissuemesh::volume::detail

// The tet shape measures and face numbering, where they live (core/tet_shape.h): checked on tets whose
// angles are known by hand. Reports, charts, the improver and tm-solve quote these numbers.
#include <cmath>

#include <gtest/gtest.h>

#include "core/tet_shape.h"

namespace tissuemesh::testing {
namespace {

TetMesh one_tet(const std::array<Vec3, 4>& corners)
{
    TetMesh mesh;
    mesh.vertices.assign(corners.begin(), corners.end());
    mesh.tets = {{0, 1, 2, 3}};
    mesh.tet_labels = {1};
    return mesh;
}

// Found in review: tet_shape lived in volume/check_mesh.h though render/ and tm-solve use it.
TEST(TetShape, TetShapeLivesInCoreAndARegularTetHasItsKnownAngles)
{
    const double s = 1 / std::sqrt(2.0);
    const TetShape shape = tet_shape(one_tet({Vec3{1, 0, -s}, Vec3{-1, 0, -s}, Vec3{0, 1, s}, Vec3{0, -1, s}}), 0);
    const double regular = std::acos(1.0 / 3) * 180 / 3.14159265358979323846; // 70.53 degrees
    EXPECT_NEAR(shape.min_dihedral_deg, regular, 1e-9);
    EXPECT_NEAR(shape.max_dihedral_deg, regular, 1e-9);
    EXPECT_NEAR(shape.radius_edge_ratio, std::sqrt(6.0) / 4, 1e-12); // circumradius sqrt(6)/4 of edge 1
}

TEST(TetShape, TheCornerTetHasRightAndSixtyDegreeAnglesAndAFlatTetHasNoRatio)
{
    // The corner of the unit cube: three right angles at the axes' edges, arccos(1/sqrt 3) = 54.7 at the others.
    const TetShape corner = tet_shape(one_tet({Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}}), 0);
    EXPECT_NEAR(corner.max_dihedral_deg, 90, 1e-9);
    EXPECT_NEAR(corner.min_dihedral_deg, std::acos(1 / std::sqrt(3.0)) * 180 / 3.14159265358979323846, 1e-9);
    EXPECT_NEAR(corner.radius_edge_ratio, (std::sqrt(3.0) / 2) / 1.0, 1e-12);
    const TetShape flat = tet_shape(one_tet({Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{1, 1, 0}}), 0);
    EXPECT_NEAR(flat.min_dihedral_deg, 0, 1e-9);
    EXPECT_TRUE(std::isinf(flat.radius_edge_ratio));
}

// One face numbering for the project: face k is opposite corner k and its normal points away from it.
TEST(TetShape, EveryFaceIsOppositeItsCornerAndFacesOutOfAPositiveTet)
{
    const std::array<Vec3, 4> p{Vec3{0, 0, 0}, Vec3{2, 0, 0}, Vec3{0.3, 1.5, 0}, Vec3{0.4, 0.2, 1.1}};
    ASSERT_GT(dot(p[1] - p[0], cross(p[2] - p[0], p[3] - p[0])), 0);
    for (int k = 0; k < 4; ++k) {
        for (int c = 0; c < 3; ++c) EXPECT_NE(tet_faces[k][c], k);
        const Vec3& a = p[tet_faces[k][0]];
        const Vec3 normal = cross(p[tet_faces[k][1]] - a, p[tet_faces[k][2]] - a);
        EXPECT_LT(dot(normal, p[k] - a), 0) << "face " << k;
    }
}

} // namespace
} // namespace tissuemesh::testing

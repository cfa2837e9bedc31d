// Regression of issue 32's "the Kuhn rule is encoded twice": assess_elements() sampled sub-voxel tets by its
// own copy of the extraction's rule (kuhn_label), which ignored the priority rule's split cubes, so on a
// priority-extracted image it disagreed with the surfaces near thin tissues. Now both use
// surface::ExtractedTissue; here a tet inside a split cube gets the tissue the extracted surface puts there.
#include <gtest/gtest.h>

#include <limits>

#include "surface/extract_interfaces.h"
#include "volume/assess.h"
#include "volume/check_mesh.h"

namespace tissuemesh::volume {
namespace {

/// 4^3 voxels of tissue 2 but for tissue 1 at (2,1,1) and (1,2,1): the face z = 1 of the cube between voxels
/// (1,1,1) and (2,2,2) is a checkerboard for tissue 1, so with tissue 1 listed in the priority that cube is
/// split around its centre (1.5, 1.5, 1.5), which is tissue 1; the plain Kuhn rule puts tissue 2 there (its
/// main diagonal joins two voxels of tissue 2).
LabelImage checkerboard_face_image()
{
    LabelImage image({4, 4, 4}, {1, 1, 1}, {0, 0, 0}, identity_matrix(), 2);
    image.at(2, 1, 1) = 1;
    image.at(1, 2, 1) = 1;
    return image;
}

/// A tet of edge 0.15 voxel next to the cube centre: it holds no voxel centre, so assess samples it.
TetMesh tet_at_cube_centre(Label tissue)
{
    TetMesh mesh;
    mesh.vertices = {{1.45, 1.45, 1.45}, {1.6, 1.45, 1.45}, {1.45, 1.6, 1.45}, {1.45, 1.45, 1.6}};
    mesh.tets = {{0, 1, 2, 3}};
    mesh.tet_labels = {tissue};
    return mesh;
}

/// The tissue the extracted complex puts at `p`, read off the complex alone: the side of the first triangle
/// that a ray from `p` crosses (the direction is generic, so the ray meets no edge).
Label first_hit_tissue(const InterfaceComplex& complex, const Vec3& p)
{
    const Vec3 direction{0.8123, 0.4311, 0.3917};
    double nearest = std::numeric_limits<double>::infinity();
    Label tissue = 0;
    for (std::size_t t = 0; t < complex.triangles.size(); ++t) {
        const auto& tri = complex.triangles[t];
        const Vec3 a = complex.vertices[tri[0]], e1 = complex.vertices[tri[1]] - a, e2 = complex.vertices[tri[2]] - a;
        const Vec3 h = cross(direction, e2);
        const double det = dot(e1, h);
        if (std::abs(det) < 1e-12) continue;
        const Vec3 s = p - a;
        const double u = dot(s, h) / det, v = dot(direction, cross(s, e1)) / det;
        const double along = dot(e2, cross(s, e1)) / det;
        if (u < 0 || v < 0 || u + v > 1 || along <= 0 || along >= nearest) continue;
        nearest = along;
        // Normals point from `from` into `to`: a ray leaving along the normal starts on the `from` side.
        tissue = dot(direction, cross(e1, e2)) > 0 ? complex.sides[t].from : complex.sides[t].to;
    }
    return tissue;
}

TEST(KuhnRuleEncodedTwice, AssessSamplesAPrioritySplitCubeAsTheExtractionDoes)
{
    const LabelImage image = checkerboard_face_image();
    const std::map<Label, int> priority{{1, 1}};
    const TetMesh mesh = tet_at_cube_centre(2);
    const Vec3 centroid{1.4875, 1.4875, 1.4875};
    const Label extracted = first_hit_tissue(surface::extract_interfaces(image, {.priority = priority}), centroid);
    ASSERT_EQ(extracted, 1);
    const Assessment a = assess_elements(mesh, image, {.extract_priority = priority});
    ASSERT_EQ(a.sampled[0], 1);
    EXPECT_EQ(a.majority[0], extracted); // the old kuhn_label gave 2 here
    EXPECT_GT(a.error_volume_mm3[0], 0.0);
}

TEST(KuhnRuleEncodedTwice, WithoutAPriorityAssessKeepsThePlainKuhnRule)
{
    const LabelImage image = checkerboard_face_image();
    const Vec3 centroid{1.4875, 1.4875, 1.4875};
    const Label extracted = first_hit_tissue(surface::extract_interfaces(image), centroid);
    ASSERT_EQ(extracted, 2);
    const Assessment a = assess_elements(tet_at_cube_centre(2), image);
    ASSERT_EQ(a.sampled[0], 1);
    EXPECT_EQ(a.majority[0], extracted);
    EXPECT_EQ(a.error_volume_mm3[0], 0.0);
}

} // namespace
} // namespace tissuemesh::volume

#include "volume/rasterize.h"

#include <algorithm>
#include <cmath>

namespace tissuemesh::volume {
namespace {

/// The infinitesimal-displacement rule for a centre exactly on a face plane with normal n.
bool perturbed_positive(const Vec3& n)
{
    if (n[0] != 0) return n[0] > 0;
    if (n[1] != 0) return n[1] > 0;
    return n[2] > 0;
}

/// A face in canonical order (ascending vertex index): the plane test is computed identically for
/// both tets sharing it. `flip` tells whether the tet's interior is on the negative side.
struct FaceTest {
    Vec3 a, normal;
    bool flip;
    bool contains(const Vec3& p) const
    {
        const double side = dot(normal, p - a);
        const bool positive = side != 0 ? side > 0 : perturbed_positive(normal);
        return positive != flip;
    }
};

FaceTest make_face(const std::vector<Vec3>& points, std::uint32_t i, std::uint32_t j, std::uint32_t k,
                   const Vec3& opposite)
{
    std::array<std::uint32_t, 3> v{i, j, k};
    std::sort(v.begin(), v.end());
    FaceTest face{points[v[0]], cross(points[v[1]] - points[v[0]], points[v[2]] - points[v[0]]), false};
    face.flip = dot(face.normal, opposite - face.a) < 0;
    return face;
}

} // namespace

std::vector<std::int32_t> rasterize_tets(const TetMesh& mesh, const LabelImage& image, const Progress& progress)
{
    std::vector<std::int32_t> owner(image.voxel_count(), -1);
    std::vector<Vec3> points(mesh.vertices.size());
    for (std::size_t v = 0; v < points.size(); ++v) points[v] = image.world_to_index(mesh.vertices[v]);
    const Dims& dims = image.dims();
    ProgressTicker ticker(progress, "rasterize", mesh.tets.size());
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& tet = mesh.tets[t];
        const std::array<FaceTest, 4> faces{make_face(points, tet[1], tet[2], tet[3], points[tet[0]]),
                                            make_face(points, tet[0], tet[2], tet[3], points[tet[1]]),
                                            make_face(points, tet[0], tet[1], tet[3], points[tet[2]]),
                                            make_face(points, tet[0], tet[1], tet[2], points[tet[3]])};
        std::array<std::int64_t, 3> lo, hi;
        for (int axis = 0; axis < 3; ++axis) {
            double min = points[tet[0]][axis], max = min;
            for (int c = 1; c < 4; ++c)
                min = std::min(min, points[tet[c]][axis]), max = std::max(max, points[tet[c]][axis]);
            lo[axis] = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::ceil(min)));
            hi[axis] = std::min<std::int64_t>(static_cast<std::int64_t>(dims[axis]) - 1,
                                              static_cast<std::int64_t>(std::floor(max)));
        }
        for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
            for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
                for (std::int64_t i = lo[0]; i <= hi[0]; ++i) {
                    const Vec3 p{static_cast<double>(i), static_cast<double>(j), static_cast<double>(k)};
                    if (faces[0].contains(p) && faces[1].contains(p) && faces[2].contains(p) && faces[3].contains(p))
                        owner[image.linear_index(static_cast<std::size_t>(i), static_cast<std::size_t>(j),
                                                 static_cast<std::size_t>(k))] = static_cast<std::int32_t>(t);
                }
        ticker.step();
    }
    return owner;
}

} // namespace tissuemesh::volume

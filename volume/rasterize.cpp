#include "volume/rasterize.h"

#include <algorithm>
#include <cmath>

namespace tissuemesh::volume {
namespace {

/// A centre this close to a tet (in voxels) that no tet claims is given to it: the tie rule is exact only for exact
/// plane tests, and a centre on an edge or a node of the mesh (TetGen and phantoms put nodes on the grid) may be
/// refused by every tet around it when the tests round differently (measured: 8 centres of the 4 mm sphere head).
constexpr double near_voxels = 1e-9;

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
    double slack; ///< how far (in index units, times |normal|) a point may lie outside and still be near
    bool flip;
    bool boundary = false; ///< on the mesh's outer boundary: near only what the rule puts inside
    bool contains(const Vec3& p) const
    {
        const double side = dot(normal, p - a);
        const bool positive = side != 0 ? side > 0 : perturbed_positive(normal);
        return positive != flip;
    }
    /// Whether p lies inside or within the slack of the face's plane (on the tet's side). A centre on the outer
    /// boundary keeps the rule's half-open answer: no neighbour can round it away.
    bool near(const Vec3& p) const
    {
        if (boundary) return contains(p);
        const double side = dot(normal, p - a);
        return flip ? side <= slack : side >= -slack;
    }
};

FaceTest make_face(const std::vector<Vec3>& points, std::uint32_t i, std::uint32_t j, std::uint32_t k,
                   const Vec3& opposite)
{
    std::array<std::uint32_t, 3> v{i, j, k};
    std::sort(v.begin(), v.end());
    FaceTest face{points[v[0]], cross(points[v[1]] - points[v[0]], points[v[2]] - points[v[0]]), 0, false};
    face.flip = dot(face.normal, opposite - face.a) < 0;
    face.slack = near_voxels * norm(face.normal);
    return face;
}

/// A centre only near tet t (held by none so far) is marked -2 - t until the end.
std::int32_t near_mark(std::size_t t) { return -2 - static_cast<std::int32_t>(t); }

} // namespace

std::vector<std::int32_t> rasterize_tets(const TetMesh& mesh, const LabelImage& image, const Progress& progress)
{
    return rasterize_tets(mesh, image, TetAdjacency(mesh.tets, mesh.vertices.size()), progress);
}

std::vector<std::int32_t> rasterize_tets(const TetMesh& mesh, const LabelImage& image, const TetAdjacency& adjacency,
                                         const Progress& progress)
{
    std::vector<std::int32_t> owner(image.voxel_count(), -1);
    std::vector<Vec3> points(mesh.vertices.size());
    for (std::size_t v = 0; v < points.size(); ++v) points[v] = image.world_to_index(mesh.vertices[v]);
    const Dims& dims = image.dims();
    ProgressTicker ticker(progress, "rasterize", mesh.tets.size());
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& tet = mesh.tets[t];
        std::array<FaceTest, 4> faces{make_face(points, tet[1], tet[2], tet[3], points[tet[0]]),
                                      make_face(points, tet[0], tet[2], tet[3], points[tet[1]]),
                                      make_face(points, tet[0], tet[1], tet[3], points[tet[2]]),
                                      make_face(points, tet[0], tet[1], tet[2], points[tet[3]])};
        for (int k = 0; k < 4; ++k) faces[k].boundary = adjacency.holders(t, k) == 1; // face k: opposite corner k
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
                    std::int32_t& o = owner[image.linear_index(static_cast<std::size_t>(i), static_cast<std::size_t>(j),
                                                               static_cast<std::size_t>(k))];
                    if (faces[0].contains(p) && faces[1].contains(p) && faces[2].contains(p) && faces[3].contains(p))
                        o = static_cast<std::int32_t>(t);
                    else if (o == -1 && faces[0].near(p) && faces[1].near(p) && faces[2].near(p) && faces[3].near(p))
                        o = near_mark(t); // claimed by the first tet it is near, unless a tet holds it
                }
        ticker.step();
    }
    for (std::int32_t& o : owner)
        if (o < -1) o = -o - 2; // only near a tet: that tet
    return owner;
}

} // namespace tissuemesh::volume

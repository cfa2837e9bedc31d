#include "fem/source_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include "core/error.h"
#include "core/tet_adjacency.h"
#include "core/tet_shape.h"
#include "fem/detail/nearest_on_triangle.h"
#include "fem/detail/point_location.h"

namespace tissuemesh::fem {
namespace {

bool chosen(const std::vector<Label>& tissues, Label label)
{
    return std::find(tissues.begin(), tissues.end(), label) != tissues.end();
}

// The faces of the chosen tissues' tets that face another tissue or the outside, bucketed in cubes of
// `cell_mm`, for "is any such face within d of this point".
class BoundaryFaces {
public:
    BoundaryFaces(const TetMesh& mesh, const std::vector<Label>& tissues, double cell_mm) : mesh_(mesh), cell_(cell_mm)
    {
        const TetAdjacency adjacency(mesh.tets, mesh.vertex_count());
        for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
            if (!chosen(tissues, mesh.tet_labels[t])) continue;
            for (int k = 0; k < 4; ++k) {
                const std::uint32_t other = adjacency.across(t, k);
                if (other != no_tet && chosen(tissues, mesh.tet_labels[other])) continue;
                const Triangle face{mesh.tets[t][tet_faces[k][0]], mesh.tets[t][tet_faces[k][1]],
                                    mesh.tets[t][tet_faces[k][2]]};
                Vec3 low = mesh.vertices[face[0]], high = low;
                for (const std::uint32_t v : face)
                    for (int a = 0; a < 3; ++a)
                        low[a] = std::min(low[a], mesh.vertices[v][a]),
                        high[a] = std::max(high[a], mesh.vertices[v][a]);
                const auto from = cell_of(low), to = cell_of(high);
                for (std::int64_t z = from[2]; z <= to[2]; ++z)
                    for (std::int64_t y = from[1]; y <= to[1]; ++y)
                        for (std::int64_t x = from[0]; x <= to[0]; ++x) cells_[key(x, y, z)].push_back(faces_.size());
                faces_.push_back(face);
            }
        }
    }

    bool within(const Vec3& point, double distance_mm) const
    {
        const auto from = cell_of(point - Vec3{distance_mm, distance_mm, distance_mm});
        const auto to = cell_of(point + Vec3{distance_mm, distance_mm, distance_mm});
        for (std::int64_t z = from[2]; z <= to[2]; ++z)
            for (std::int64_t y = from[1]; y <= to[1]; ++y)
                for (std::int64_t x = from[0]; x <= to[0]; ++x) {
                    const auto cell = cells_.find(key(x, y, z));
                    if (cell == cells_.end()) continue;
                    for (const std::size_t f : cell->second) {
                        const Vec3 &a = mesh_.vertices[faces_[f][0]], &b = mesh_.vertices[faces_[f][1]],
                                   &c = mesh_.vertices[faces_[f][2]];
                        const std::array<double, 3> w = detail::nearest_on_triangle(point, a, b, c);
                        if (distance(point, w[0] * a + w[1] * b + w[2] * c) < distance_mm) return true;
                    }
                }
        return false;
    }

private:
    std::array<std::int64_t, 3> cell_of(const Vec3& p) const
    {
        return {static_cast<std::int64_t>(std::floor(p[0] / cell_)),
                static_cast<std::int64_t>(std::floor(p[1] / cell_)),
                static_cast<std::int64_t>(std::floor(p[2] / cell_))};
    }
    static std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z)
    {
        const auto part = [](std::int64_t v) { return static_cast<std::uint64_t>(v + (1 << 20)) & 0x1fffff; };
        return part(x) | part(y) << 21 | part(z) << 42;
    }

    const TetMesh& mesh_;
    double cell_;
    std::vector<Triangle> faces_;
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells_;
};

} // namespace

std::vector<Vec3> source_grid(const TetMesh& mesh, const SourceGridOptions& options)
{
    if (!(options.spacing_mm > 0) || !std::isfinite(options.spacing_mm))
        throw InputError(concat("source grid: spacing ", options.spacing_mm, " mm; give a positive length"));
    if (!(options.min_distance_mm >= 0) || !std::isfinite(options.min_distance_mm))
        throw InputError(
            concat("source grid: distance ", options.min_distance_mm, " mm; give a length of 0 mm or more"));
    if (options.tissues.empty()) throw InputError("source grid: no tissue chosen; name the tissues the sources lie in");
    Vec3 low{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
             std::numeric_limits<double>::infinity()};
    Vec3 high = -1.0 * low;
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
        if (!chosen(options.tissues, mesh.tet_labels[t])) continue;
        for (const std::uint32_t v : mesh.tets[t])
            for (int a = 0; a < 3; ++a)
                low[a] = std::min(low[a], mesh.vertices[v][a]), high[a] = std::max(high[a], mesh.vertices[v][a]);
    }
    for (const Label label : options.tissues)
        if (std::find(mesh.tet_labels.begin(), mesh.tet_labels.end(), label) == mesh.tet_labels.end())
            throw InputError(concat("source grid: tissue ", label, " has no tet in the mesh; choose tissues it has"));
    std::array<std::int64_t, 3> first{}, last{};
    double candidates = 1;
    for (int a = 0; a < 3; ++a) {
        first[a] = static_cast<std::int64_t>(std::ceil(low[a] / options.spacing_mm));
        last[a] = static_cast<std::int64_t>(std::floor(high[a] / options.spacing_mm));
        candidates *= static_cast<double>(std::max<std::int64_t>(0, last[a] - first[a] + 1));
    }
    if (candidates > static_cast<double>(options.max_points))
        throw InputError(concat("source grid: ", candidates, " grid points at ", options.spacing_mm,
                                " mm in the tissues' box, ", "more than ", options.max_points,
                                "; choose a larger spacing"));
    std::vector<Vec3> points;
    for (std::int64_t z = first[2]; z <= last[2]; ++z)
        for (std::int64_t y = first[1]; y <= last[1]; ++y)
            for (std::int64_t x = first[0]; x <= last[0]; ++x)
                points.push_back(options.spacing_mm *
                                 Vec3{static_cast<double>(x), static_cast<double>(y), static_cast<double>(z)});
    const std::vector<std::uint32_t> tets = detail::locate_points(mesh, points);
    std::vector<Vec3> inside;
    for (std::size_t p = 0; p < points.size(); ++p)
        if (tets[p] != detail::outside_mesh && chosen(options.tissues, mesh.tet_labels[tets[p]]))
            inside.push_back(points[p]);
    if (options.min_distance_mm <= 0) return inside;
    const BoundaryFaces faces(mesh, options.tissues, std::max(options.min_distance_mm, 0.5 * options.spacing_mm));
    std::vector<Vec3> kept;
    for (const Vec3& point : inside)
        if (!faces.within(point, options.min_distance_mm)) kept.push_back(point);
    return kept;
}

} // namespace tissuemesh::fem

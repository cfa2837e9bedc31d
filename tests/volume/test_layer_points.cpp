// Nodes inside the tissue layers (volume/detail/layer_points.h), given to TetGen by tetrahedralize().
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "image/phantom.h"
#include "surface/detail/triangle_distance.h"
#include "surface/extract_interfaces.h"
#include "volume/check_mesh.h"
#include "volume/detail/layer_points.h"
#include "volume/tetrahedralize.h"

namespace tissuemesh {
namespace {

/// A 10 mm shell around a ball split in two (3 mm voxels): layers several edges thick, and a junction.
InterfaceComplex shell_and_ball()
{
    const image::Phantom phantom = image::make_phantom("junction", {.voxel_mm = 3});
    return surface::extract_interfaces(phantom.image);
}

/// The smallest mean edge length of a vertex.
double smallest_mean_edge(const InterfaceComplex& complex)
{
    std::vector<double> sum(complex.vertices.size(), 0);
    std::vector<int> count(complex.vertices.size(), 0);
    for (const Triangle& tri : complex.triangles)
        for (int k = 0; k < 3; ++k) {
            sum[tri[k]] += distance(complex.vertices[tri[k]], complex.vertices[tri[(k + 1) % 3]]) +
                           distance(complex.vertices[tri[k]], complex.vertices[tri[(k + 2) % 3]]);
            count[tri[k]] += 2;
        }
    double smallest = 1e300;
    for (std::size_t v = 0; v < sum.size(); ++v)
        if (count[v] > 0) smallest = std::min(smallest, sum[v] / count[v]);
    return smallest;
}

/// Tets whose four nodes all lie on interface faces.
std::size_t tets_on_interfaces_only(const TetMesh& mesh)
{
    std::vector<char> on_interface(mesh.vertices.size(), 0);
    for (const Triangle& face : mesh.faces)
        for (const std::uint32_t v : face) on_interface[v] = 1;
    return static_cast<std::size_t>(std::count_if(mesh.tets.begin(), mesh.tets.end(), [&](const Tet& tet) {
        return std::all_of(tet.begin(), tet.end(), [&](std::uint32_t v) { return on_interface[v] != 0; });
    }));
}

TEST(LayerPoints, LieOffEveryTriangleAndApartInVertexOrder)
{
    const InterfaceComplex complex = shell_and_ball();
    const volume::detail::LayerPointsOptions options;
    const std::vector<Vec3> points = volume::detail::layer_points(complex, options);
    ASSERT_GT(points.size(), 100u);
    EXPECT_EQ(volume::detail::layer_points(complex, options), points) << "not deterministic";
    // Every point is clear of every triangle: at least the clearance times the smallest offset (a fraction of its
    // vertex's mean edge).
    const double edge = smallest_mean_edge(complex);
    std::printf("[ figures  ] %zu points, %zu triangles, smallest mean edge %.2f mm\n", points.size(),
                complex.triangles.size(), edge);
    // Brute force, with a box test first: only the distances under the bound matter.
    const double bound = options.clearance * options.min_offset_per_edge * edge;
    double nearest = bound;
    for (const Triangle& tri : complex.triangles) {
        const surface::detail::TriangleCorners c{complex.vertices[tri[0]], complex.vertices[tri[1]],
                                                 complex.vertices[tri[2]]};
        Vec3 low = c[0], high = c[0];
        for (const Vec3& corner : c)
            for (int i = 0; i < 3; ++i) {
                low[i] = std::min(low[i], corner[i] - bound);
                high[i] = std::max(high[i], corner[i] + bound);
            }
        for (const Vec3& p : points) {
            if (p[0] < low[0] || p[0] > high[0] || p[1] < low[1] || p[1] > high[1] || p[2] < low[2] || p[2] > high[2])
                continue;
            nearest = std::min(nearest, distance(p, surface::detail::closest_point_on_triangle(p, c)));
        }
    }
    EXPECT_GE(nearest, bound);
    // and no two points closer than the spacing of the smaller edges allows.
    double closest = 1e300;
    for (std::size_t i = 0; i < points.size(); ++i)
        for (std::size_t j = i + 1; j < points.size(); ++j) closest = std::min(closest, distance(points[i], points[j]));
    EXPECT_GT(closest, options.spacing_per_edge * edge);
}

TEST(LayerPoints, TetrahedralizeUsesThemInsideTheTissuesOnly)
{
    const InterfaceComplex complex = shell_and_ball();
    volume::TetrahedralizeReport plain_report, report;
    const TetMesh plain = volume::tetrahedralize(complex, {.improve = false}, {}, &plain_report);
    const TetMesh mesh = volume::tetrahedralize(complex, {.layer_points = true, .improve = false}, {}, &report);
    EXPECT_EQ(report.layer_points, volume::detail::layer_points(complex).size());
    // Every given point is a node of a meshed tet: none fell outside the object (where its tets would be dropped).
    EXPECT_EQ(mesh.vertices.size(), complex.vertices.size() + report.layer_points + report.steiner_points);
    const volume::MeshCheckReport check = volume::check_mesh(mesh), plain_check = volume::check_mesh(plain);
    ASSERT_TRUE(check.ok()) << (check.problems.empty() ? "" : check.problems.front());
    // The interfaces are kept, so every tissue's volume is the same to rounding.
    for (const auto& [label, stats] : plain_check.tissues)
        EXPECT_NEAR(check.tissues.at(label).volume_mm3, stats.volume_mm3, 1e-9 * stats.volume_mm3)
            << "tissue " << label;
    EXPECT_EQ(mesh.faces.size(), plain.faces.size());
    // Fewer tets span a layer from side to side (measured: see the printed figures).
    const std::size_t spanning = tets_on_interfaces_only(mesh), plain_spanning = tets_on_interfaces_only(plain);
    std::printf("[ figures  ] %zu layer points: tets on interface nodes only %zu -> %zu of %zu -> %zu\n",
                report.layer_points, plain_spanning, spanning, plain.tets.size(), mesh.tets.size());
    EXPECT_LT(spanning, plain_spanning);
}

} // namespace
} // namespace tissuemesh

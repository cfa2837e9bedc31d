#include "fem_meshes.h"

#include <array>
#include <cmath>
#include <map>
#include <random>
#include <utility>

#include "volume/tetrahedralize.h"

namespace tissuemesh::testing {

TetMesh box_mesh(int n, double size_mm, double jitter, const std::function<Label(const Vec3&)>& label_of)
{
    TetMesh mesh;
    const double h = size_mm / n;
    const auto index = [n](int i, int j, int k) { return static_cast<std::uint32_t>((k * (n + 1) + j) * (n + 1) + i); };
    std::mt19937 random(12345);
    std::uniform_real_distribution<double> offset(-jitter * h, jitter * h);
    for (int k = 0; k <= n; ++k)
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                Vec3 p{i * h, j * h, k * h};
                const bool interior = i > 0 && i < n && j > 0 && j < n && k > 0 && k < n;
                for (double& c : p) c += interior ? offset(random) : 0.0;
                mesh.vertices.push_back(p);
            }
    // Kuhn subdivision: one tet per axis order, along the path from corner 000 to corner 111.
    static constexpr std::array<std::array<int, 3>, 6> orders = {
        {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                for (const auto& order : orders) {
                    std::array<int, 3> corner{i, j, k};
                    Tet tet{};
                    tet[0] = index(corner[0], corner[1], corner[2]);
                    for (int s = 0; s < 3; ++s) {
                        ++corner[order[s]];
                        tet[s + 1] = index(corner[0], corner[1], corner[2]);
                    }
                    mesh.tets.push_back(tet);
                    if (signed_volume(mesh, mesh.tets.size() - 1) < 0)
                        std::swap(mesh.tets.back()[2], mesh.tets.back()[3]);
                    Vec3 centroid{0, 0, 0};
                    for (std::uint32_t v : mesh.tets.back()) centroid = centroid + 0.25 * mesh.vertices[v];
                    mesh.tet_labels.push_back(label_of ? label_of(centroid) : Label{1});
                }
    mesh.names = {{1, "one"}, {2, "two"}};
    return mesh;
}

InterfaceComplex icosphere(int levels, double radius_mm)
{
    const double g = (1 + std::sqrt(5.0)) / 2;
    InterfaceComplex sphere;
    sphere.vertices = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                       {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
    sphere.triangles = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                        {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
        const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::minmax(a, b);
            const auto [found, inserted] =
                midpoints.try_emplace(key, static_cast<std::uint32_t>(sphere.vertices.size()));
            if (inserted) sphere.vertices.push_back(0.5 * (sphere.vertices[a] + sphere.vertices[b]));
            return found->second;
        };
        std::vector<Triangle> finer;
        for (const Triangle& t : sphere.triangles) {
            const std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
            finer.insert(finer.end(), {{t[0], ab, ca}, {t[1], bc, ab}, {t[2], ca, bc}, {ab, bc, ca}});
        }
        sphere.triangles = std::move(finer);
    }
    for (Vec3& v : sphere.vertices) v = (radius_mm / norm(v)) * v;
    sphere.sides.assign(sphere.triangles.size(), LabelPair{0, 1});
    return sphere;
}

TetMesh shell_mesh(const std::vector<double>& radii_mm, int levels, double max_volume_mm3)
{
    InterfaceComplex complex;
    complex.background = 0;
    const auto count = static_cast<Label>(radii_mm.size());
    for (Label k = 0; k < count; ++k) {
        const InterfaceComplex sphere = icosphere(levels, radii_mm[k]);
        const auto base = static_cast<std::uint32_t>(complex.vertices.size());
        complex.vertices.insert(complex.vertices.end(), sphere.vertices.begin(), sphere.vertices.end());
        // Outward normal: from the tissue inside sphere k (k; 0 = cavity) to the one outside (k+1; none
        // outside the last sphere).
        const LabelPair pair{k, static_cast<Label>(k + 1 == count ? 0 : k + 1)};
        for (const Triangle& t : sphere.triangles) complex.add_triangle({base + t[0], base + t[1], base + t[2]}, pair);
        complex.names[static_cast<Label>(k + 1)] = "shell" + std::to_string(k + 1);
    }
    complex.names.erase(count);
    complex.names[0] = "background";
    volume::TetrahedralizeOptions options;
    options.max_volume_mm3 = max_volume_mm3;
    options.mesh_background_cavities = false;
    return volume::tetrahedralize(complex, options);
}

TetMesh four_shell_head(int levels, double max_volume_mm3)
{
    InterfaceComplex complex;
    const double radii[4] = {78, 80, 86, 92};
    for (int k = 0; k < 4; ++k) {
        const InterfaceComplex sphere = icosphere(levels, radii[k]);
        const auto base = static_cast<std::uint32_t>(complex.vertices.size());
        complex.vertices.insert(complex.vertices.end(), sphere.vertices.begin(), sphere.vertices.end());
        const LabelPair pair{static_cast<Label>(4 - k), static_cast<Label>(3 - k)}; // inside -> outside
        for (const Triangle& t : sphere.triangles) complex.add_triangle({base + t[0], base + t[1], base + t[2]}, pair);
    }
    complex.names = {{0, "background"}, {1, "scalp"}, {2, "skull"}, {3, "csf"}, {4, "brain"}};
    volume::TetrahedralizeOptions options;
    options.max_volume_mm3 = max_volume_mm3;
    return volume::tetrahedralize(complex, options);
}

TetMesh ball_mesh(double radius_mm, int levels, double max_volume_mm3)
{
    InterfaceComplex complex = icosphere(levels, radius_mm);
    complex.sides.assign(complex.triangles.size(), LabelPair{1, 0}); // brain inside, background outside
    complex.names = {{0, "background"}, {1, "brain"}};
    volume::TetrahedralizeOptions options;
    options.max_volume_mm3 = max_volume_mm3;
    return volume::tetrahedralize(complex, options);
}

} // namespace tissuemesh::testing

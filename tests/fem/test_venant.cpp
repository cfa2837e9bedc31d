// The multipolar Venant source model (fem/detail/venant.h): the monopoles carry the dipole's moments, stay in
// the source tissue, and reproduce the potential of a dipole in a homogeneous sphere.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "fem/detail/venant.h"
#include "fem/outer_boundary.h"
#include "fem/solve_potential.h"
#include "fem/sphere_series.h"
#include "fem_meshes.h"

namespace tissuemesh::fem {
namespace {

// Moments of the monopoles about `x0` (mm): net current (A), first moment (A*m), traceless second moment
// (A*m^2, Frobenius norm).
struct Moments {
    double net = 0, largest = 0;
    Vec3 first{0, 0, 0};
    double traceless_second = 0;
};

Moments moments(const TetMesh& mesh, const detail::Monopoles& monopoles, const Vec3& x0)
{
    Moments m;
    double s[3][3] = {};
    for (std::size_t k = 0; k < monopoles.nodes.size(); ++k) {
        const double q = monopoles.currents_a[k];
        const Vec3 d = 1e-3 * (mesh.vertices[monopoles.nodes[k]] - x0);
        m.net += q;
        m.largest = std::max(m.largest, std::abs(q));
        m.first = m.first + q * d;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) s[i][j] += q * d[static_cast<std::size_t>(i)] * d[static_cast<std::size_t>(j)];
    }
    const double mean = (s[0][0] + s[1][1] + s[2][2]) / 3;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m.traceless_second += std::pow(s[i][j] - (i == j ? mean : 0), 2);
    m.traceless_second = std::sqrt(m.traceless_second);
    return m;
}

// A jittered box of 2 mm cubes; the dipole 0.3 mm from node (3, 3, 3) of the grid, so that node is the
// nearest corner of the dipole's tet.
TEST(Venant, MonopolesCarryTheDipoleMomentAndNoNetCurrent)
{
    const TetMesh mesh = testing::box_mesh(6, 12.0, 0.15);
    const std::uint32_t centre = (3 * 7 + 3) * 7 + 3;
    const Vec3 position = mesh.vertices[centre] + Vec3{0.2, -0.1, 0.2};
    const Vec3 moment{1e-8, -2e-8, 0.5e-8};
    const Conductivities sigma = resolve_conductivities(mesh, {{"1", isotropic(0.33)}});
    const detail::Monopoles monopoles = detail::venant_monopoles(mesh, sigma, {position, moment}, 0, {});
    // The nodes: the centre node and every node of the tets around it.
    std::vector<std::uint32_t> star;
    for (const Tet& tet : mesh.tets)
        if (std::find(tet.begin(), tet.end(), centre) != tet.end()) star.insert(star.end(), tet.begin(), tet.end());
    std::sort(star.begin(), star.end());
    star.erase(std::unique(star.begin(), star.end()), star.end());
    EXPECT_EQ(monopoles.nodes, star);
    const Moments m = moments(mesh, monopoles, position);
    // Orders 0 and 1 are imposed exactly: round-off of currents ~1e-6 A.
    EXPECT_LT(std::abs(m.net), 1e-12 * m.largest);
    for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(m.first[i], moment[i], 1e-12 * norm(moment)) << i;
    // 15 nodes leave room to cancel the traceless second moment too; what is left is the regulariser's
    // trade-off (measured 1.3e-15 A*m^2, about 3e-5 of |p| times the 2 mm edge). Partial integration
    // leaves 0.2 to 3 times |p| times the tet's longest edge (docs/fem.md), so 1e-3 tells the two apart.
    std::printf("[venant] %zu nodes, largest current %.3e A, traceless second moment %.3e A*m^2\n",
                monopoles.nodes.size(), m.largest, m.traceless_second);
    EXPECT_LT(m.traceless_second, 1e-3 * norm(moment) * 2e-3);
}

// Two tissues of different conductivity meet at x = 6 mm; the dipole sits in tissue 1 next to the
// interface: no monopole may sit on a node that only tissue 2 has.
TEST(Venant, MonopolesStayInTheSourceTissue)
{
    const TetMesh mesh = testing::box_mesh(6, 12.0, 0.0, [](const Vec3& c) { return Label(c[0] < 6 ? 1 : 2); });
    const Vec3 position{5.7, 6.3, 5.9}; // nearest node (6, 6, 6) lies on the interface
    const Dipole dipole{position, {1e-8, 0, 0}};
    const auto nodes_of = [&](Label tissue) {
        std::vector<bool> has(mesh.vertex_count(), false);
        for (std::size_t t = 0; t < mesh.tet_count(); ++t)
            if (mesh.tet_labels[t] == tissue)
                for (const std::uint32_t v : mesh.tets[t]) has[v] = true;
        return has;
    };
    const std::vector<bool> in_source = nodes_of(1);
    const Conductivities different = resolve_conductivities(mesh, {{"1", isotropic(0.33)}, {"2", isotropic(1.79)}});
    const detail::Monopoles inside = detail::venant_monopoles(mesh, different, dipole, 0, {});
    for (const std::uint32_t node : inside.nodes) EXPECT_TRUE(in_source[node]) << node;
    const Moments m = moments(mesh, inside, position);
    EXPECT_NEAR(m.first[0], 1e-8, 1e-20);
    // Where both tissues conduct alike they are one medium, and the whole star takes part.
    const Conductivities same = resolve_conductivities(mesh, {{"1", isotropic(0.33)}, {"2", isotropic(0.33)}});
    const detail::Monopoles across = detail::venant_monopoles(mesh, same, dipole, 0, {});
    EXPECT_GT(across.nodes.size(), inside.nodes.size());
    EXPECT_TRUE(std::any_of(across.nodes.begin(), across.nodes.end(), [&](std::uint32_t v) { return !in_source[v]; }));
}

// The dipole at the centre of a homogeneous sphere (test_dipole.cpp: partial integration gives RDM 0.035
// there, from the quadrupole of its one source tet). Venant's monopoles have no traceless quadrupole, so
// what is left is the mesh's own error.
TEST(Venant, CentredDipoleInAHomogeneousSphere)
{
    const double radius_mm = 50;
    const TetMesh mesh = testing::ball_mesh(radius_mm, 4, 5.0);
    PotentialProblem problem;
    const Vec3 moment{0, 0.6e-8, 0.8e-8};
    problem.dipoles = {{.position_mm = {0, 0, 0}, .moment_am = moment}}; // on a node: Venant does not mind
    problem.dipole_model = DipoleModel::venant;
    const std::vector<double> phi =
        solve_potential(mesh, resolve_conductivities(mesh, {}), problem, {.relative_tolerance = 1e-12});
    std::vector<double> numeric;
    std::vector<Vec3> points;
    for (const std::uint32_t node : outer_boundary(mesh).nodes)
        numeric.push_back(phi[node]), points.push_back(mesh.vertices[node]);
    const std::vector<double> analytic = sphere_surface_potentials({{radius_mm}, {0.33}}, {0, 0, 0}, moment, points);
    const auto [rdm, mag] = compare_potentials(numeric, analytic);
    std::printf("[venant] centred dipole: RDM %.4f, MAG %.4f\n", rdm, mag);
    EXPECT_LT(rdm, 0.01);
    EXPECT_NEAR(mag, 1.0, 0.01);
}

} // namespace
} // namespace tissuemesh::fem

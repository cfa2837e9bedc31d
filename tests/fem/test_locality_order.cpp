// detail::renumber_for_locality(): the solver's copy of a mesh numbered for locality is the same mesh, and
// what the solver reports is numbered as the caller's mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "core/error.h"
#include "fem/detail/locality_order.h"
#include "fem/solve_potential.h"
#include "fem_meshes.h"
#include "tests/io/expect_error.h"

namespace tissuemesh::fem {
namespace {

TEST(LocalityOrder, RenumberedMeshIsTheSameMesh)
{
    TetMesh mesh = testing::box_mesh(6, 30.0, 0.2);
    // Scramble the input numbering, as TetGen's would be.
    std::reverse(mesh.tets.begin(), mesh.tets.end());
    std::reverse(mesh.tet_labels.begin(), mesh.tet_labels.end());
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) mesh.tet_labels[t] = static_cast<Label>(1 + t % 3);
    const detail::LocalMesh local = detail::renumber_for_locality(mesh);
    ASSERT_EQ(local.mesh.vertex_count(), mesh.vertex_count());
    ASSERT_EQ(local.mesh.tet_count(), mesh.tet_count());
    for (std::uint32_t v = 0; v < mesh.vertex_count(); ++v) {
        EXPECT_EQ(local.original[local.local[v]], v);
        EXPECT_EQ(local.mesh.vertices[local.local[v]], mesh.vertices[v]);
    }
    // The same tets (as sets of original nodes, with their labels and volumes), in an order whose first
    // nodes never decrease.
    std::multiset<std::pair<std::array<std::uint32_t, 4>, Label>> before, after;
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
        std::array<std::uint32_t, 4> tet = mesh.tets[t];
        std::sort(tet.begin(), tet.end());
        before.insert({tet, mesh.tet_labels[t]});
    }
    std::uint32_t previous_first = 0;
    for (std::size_t t = 0; t < local.mesh.tet_count(); ++t) {
        const Tet& tet = local.mesh.tets[t];
        const std::uint32_t first = *std::min_element(tet.begin(), tet.end());
        EXPECT_GE(first, previous_first);
        previous_first = first;
        EXPECT_GT(signed_volume(local.mesh, t), 0);
        std::array<std::uint32_t, 4> original{local.original[tet[0]], local.original[tet[1]], local.original[tet[2]],
                                              local.original[tet[3]]};
        std::sort(original.begin(), original.end());
        after.insert({original, local.mesh.tet_labels[t]});
    }
    EXPECT_EQ(before, after);
}

TEST(LocalityOrder, SolverMessagesNameTheCallersNodes)
{
    TetMesh mesh = testing::box_mesh(4, 20.0);
    std::reverse(mesh.vertices.begin(), mesh.vertices.end()); // a numbering far from Z-order
    const auto n = static_cast<std::uint32_t>(mesh.vertex_count());
    for (Tet& tet : mesh.tets) {
        for (std::uint32_t& v : tet) v = n - 1 - v;
    }
    for (Triangle& face : mesh.faces)
        for (std::uint32_t& v : face) v = n - 1 - v;
    const Conductivities sigma = resolve_conductivities(mesh, {{"1", isotropic(0.33)}}, false);
    PotentialProblem problem;
    problem.fixed = {{7, 7}, {0.0, 1.0}};
    // Node 7 fixed at two potentials was accepted.
    testing::expect_error<InputError>([&] { solve_potential(mesh, sigma, problem); }, {"node 7 is fixed at both"});
    // The potentials come back in the caller's numbering: nodes fixed at 0 V and 1 V keep them.
    problem.fixed = {{3, n - 4}, {0.0, 1.0}};
    const std::vector<double> phi = solve_potential(mesh, sigma, problem, {.relative_tolerance = 1e-12});
    EXPECT_EQ(phi[3], 0.0);
    EXPECT_EQ(phi[n - 4], 1.0);
    for (const double value : phi) EXPECT_TRUE(value >= -1e-9 && value <= 1 + 1e-9) << value; // maximum principle
}

} // namespace
} // namespace tissuemesh::fem

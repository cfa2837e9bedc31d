// AMG-CG on several MPI processes (tm-amg-worker under mpiexec) and the electrode's local boundary: the
// same answers as the one-process solve and the whole-mesh boundary pass.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "core/error.h"

#include "fem/outer_boundary.h"
#include "fem/solve_potential.h"
#include "fem_meshes.h"

namespace tissuemesh::fem {
namespace {

// 1 mA through a jittered 20 mm box of two tissues, between patches on two opposite faces: 29 791 nodes.
struct BoxCurrent {
    TetMesh mesh = testing::box_mesh(30, 20.0, 0.2, [](const Vec3& c) { return Label(c[0] < 10 ? 1 : 2); });
    Conductivities sigma = resolve_conductivities(mesh, {{"1", isotropic(0.33)}, {"2", isotropic(0.01)}});
    PotentialProblem problem;
    BoxCurrent()
    {
        problem.electrodes.push_back({.centre_mm = {0, 10, 10}, .radius_mm = 6, .current_a = 1e-3});
        problem.electrodes.push_back({.centre_mm = {20, 10, 10}, .radius_mm = 6, .current_a = -1e-3});
    }
};

// Collects the warnings a solve reports.
struct Warnings {
    std::string text;
    Progress progress()
    {
        return Progress({}, [this](LogLevel level, std::string_view, std::string_view message) {
            if (level == LogLevel::warning) text.append(message).append("\n");
        });
    }
};

TEST(AmgProcesses, TwoProcessesGiveTheOneProcessPotential)
{
    const BoxCurrent box;
    const SolverOptions one{.relative_tolerance = 1e-10, .processes = 1};
    SolverOptions two = one;
    two.processes = 2;
    two.min_unknowns_per_process = 5'000; // the box has 29 791 nodes
    PotentialReport report_one, report_two;
    Warnings warnings;
    const std::vector<double> phi_one = solve_potential(box.mesh, box.sigma, box.problem, one, {}, &report_one);
    const std::vector<double> phi_two =
        solve_potential(box.mesh, box.sigma, box.problem, two, warnings.progress(), &report_two);
    EXPECT_EQ(warnings.text, "");
    EXPECT_EQ(report_one.solver.processes, 1);
    ASSERT_EQ(report_two.solver.processes, 2) << warnings.text;
    EXPECT_LE(report_two.solver.relative_residual, 1e-9);
    EXPECT_GT(report_two.solver.iterations, 0);
    const auto [low, high] = std::minmax_element(phi_one.begin(), phi_one.end());
    double worst = 0;
    for (std::size_t v = 0; v < phi_one.size(); ++v) worst = std::max(worst, std::abs(phi_one[v] - phi_two[v]));
    // Both residuals are under 1e-10 relative; the potentials span (high - low) volts: 1e-7 of that span
    // leaves room for the condition number (about 1e3 here, from the 33:1 conductivity jump).
    EXPECT_LT(worst, 1e-7 * (*high - *low)) << worst << " V of " << *high - *low << " V";
}

TEST(AmgProcesses, FewUnknownsStayInOneProcess)
{
    const BoxCurrent box;
    PotentialReport report;
    solve_potential(box.mesh, box.sigma, box.problem, {.processes = 4}, {}, &report); // 29 791 < 2 x 100 000
    EXPECT_EQ(report.solver.processes, 1);
}

// Without a working MPI launcher the solve says why and runs in its own process.
TEST(AmgProcesses, MissingOrFailingMpiexecFallsBackWithAWarning)
{
    const BoxCurrent box;
    for (const auto& [launcher, reason] : {std::pair{"tm-no-such-mpiexec", "tm-no-such-mpiexec is not found"},
                                           std::pair{"false", "false exited with status 1"}}) {
        Warnings warnings;
        PotentialReport report;
        const SolverOptions options{.processes = 2, .min_unknowns_per_process = 5'000, .mpiexec = launcher};
        solve_potential(box.mesh, box.sigma, box.problem, options, warnings.progress(), &report);
        EXPECT_EQ(report.solver.processes, 1);
        EXPECT_NE(warnings.text.find(reason), std::string::npos) << warnings.text;
        EXPECT_NE(warnings.text.find("solving in one process instead"), std::string::npos) << warnings.text;
        EXPECT_LE(report.solver.relative_residual, 1e-9);
    }
}

// outer_boundary_near() is outer_boundary() cut to the ball: faces with a node inside, nodes inside.
TEST(OuterBoundaryNear, IsTheWholeBoundaryCutToTheBall)
{
    const TetMesh mesh = testing::box_mesh(8, 16.0, 0.2);
    const OuterBoundary whole = outer_boundary(mesh);
    for (const auto& [centre, radius] :
         {std::pair{Vec3{0, 0, 0}, 5.0}, std::pair{Vec3{8, 8, 16}, 4.5}, std::pair{Vec3{8, 8, 8}, 3.0},
          std::pair{Vec3{8, 8, 8}, 100.0}, std::pair{Vec3{50, 0, 0}, 10.0}, std::pair{Vec3{16, 3, 7}, 0.0}}) {
        const auto inside = [&](std::uint32_t node) { return distance(mesh.vertices[node], centre) <= radius; };
        OuterBoundary expected;
        for (const Triangle& face : whole.faces)
            if (inside(face[0]) || inside(face[1]) || inside(face[2])) expected.faces.push_back(face);
        std::copy_if(whole.nodes.begin(), whole.nodes.end(), std::back_inserter(expected.nodes), inside);
        const OuterBoundary near = outer_boundary_near(mesh, centre, radius);
        EXPECT_EQ(near.faces, expected.faces) << "ball at " << centre[0] << "," << centre[1] << "," << centre[2];
        EXPECT_EQ(near.nodes, expected.nodes);
    }
    EXPECT_EQ(outer_boundary_near(mesh, {8, 8, 8}, 3.0).faces.size(), 0u); // inside, no boundary face
    EXPECT_EQ(outer_boundary_near(mesh, {8, 8, 8}, 100.0).faces, whole.faces);
}

TEST(OuterBoundaryNear, RefusesANonFiniteBall)
{
    const TetMesh mesh = testing::box_mesh(2, 4.0);
    EXPECT_THROW(outer_boundary_near(mesh, {0, 0, 0}, std::nan("")), InputError);
    EXPECT_THROW(outer_boundary_near(mesh, {0, 0, std::nan("")}, 1.0), InputError);
    EXPECT_THROW(outer_boundary_near(mesh, {0, 0, 0}, -1.0), InputError);
}

} // namespace
} // namespace tissuemesh::fem

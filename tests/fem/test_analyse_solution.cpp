// fem::analyse_solution(), the work tm-solve's main did itself (issue 32: "tm_solve's main is 114 lines with
// OpenMP inside the tool"): on a two-tissue box with the linear potential phi = x (V, x in mm) every field is
// known exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/tet_shape.h"
#include "fem/analyse_solution.h"
#include "fem/estimate_error.h"
#include "tests/fem/fem_meshes.h"

namespace tissuemesh::fem {
namespace {

TEST(SolveMainWithOpenMpInsideTheTool, AnalyseSolutionGivesTheFieldsAndStatisticsTmSolveReports)
{
    const TetMesh mesh = testing::box_mesh(4, 10.0, 0.2, [](const Vec3& c) { return c[0] < 5 ? Label{1} : Label{2}; });
    const Conductivities sigma = resolve_conductivities(mesh, {{"1", isotropic(1.0)}, {"2", isotropic(0.25)}});
    std::vector<double> phi;
    for (const Vec3& v : mesh.vertices) phi.push_back(v[0]);
    const SolutionAnalysis a = analyse_solution(mesh, sigma, phi, {.error_indicator = true});
    // E = -grad phi = -1 V/mm = -1000 V/m along x in every tet (P1 reproduces a linear potential exactly, up to
    // rounding of the gradients: 1e-9 relative).
    ASSERT_EQ(a.e_magnitude_v_per_m.size(), mesh.tet_count());
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) EXPECT_NEAR(a.e_magnitude_v_per_m[t], 1000.0, 1e-6) << t;
    ASSERT_EQ(a.tissues.size(), 2u);
    double volume = 0;
    std::size_t tets = 0;
    for (const auto& [label, tissue] : a.tissues) {
        const double conductivity = label == 1 ? 1.0 : 0.25;
        EXPECT_NEAR(tissue.mean_e_v_per_m, 1000.0, 1e-6);
        EXPECT_NEAR(tissue.max_e_v_per_m, 1000.0, 1e-6);
        EXPECT_NEAR(tissue.mean_j_a_per_m2, 1000.0 * conductivity, 1e-6);
        volume += tissue.volume_mm3, tets += tissue.tets;
    }
    EXPECT_NEAR(volume, 1000.0, 1e-9); // the 10 mm box
    EXPECT_EQ(tets, mesh.tet_count());
    // The indicator is estimate_error()'s, and its total the root of the sum of squares.
    EXPECT_EQ(a.error_indicator, estimate_error(mesh, sigma, phi));
    double squares = 0;
    for (const double eta : a.error_indicator) squares += eta * eta;
    EXPECT_DOUBLE_EQ(a.error_indicator_total, std::sqrt(squares));
    EXPECT_GT(a.error_indicator_total, 0.0) << "the normal current jumps where sigma does";
    double smallest = 180;
    for (std::size_t t = 0; t < mesh.tet_count(); ++t)
        smallest = std::min(smallest, tet_shape(mesh, t).min_dihedral_deg);
    EXPECT_EQ(a.min_dihedral_deg, smallest);
    // Without the indicator: none computed.
    const SolutionAnalysis plain = analyse_solution(mesh, sigma, phi);
    EXPECT_TRUE(plain.error_indicator.empty());
    EXPECT_EQ(plain.error_indicator_total, 0.0);
}

} // namespace
} // namespace tissuemesh::fem

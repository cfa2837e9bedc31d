// tm-solve's AMG-CG on the slots of an MPI host file, as on a cluster without a scheduler that Open MPI knows:
// two slots on localhost stand for two nodes. The host file reaches mpiexec through an Open MPI parameter file
// (OMPI_MCA_mca_base_param_files); a host file naming an unknown node makes mpiexec fail, which shows that it is
// read. Each solve has 205 379 nodes: tm-solve gives a process at least 100 000 unknowns.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <utility>

#include "io/tet_mesh_io.h"
#include "tests/support/cli.h"

namespace tissuemesh::testing {
namespace {

namespace fs = std::filesystem;

// [0, 20]^3 mm, n^3 cubes of 6 tets (Kuhn subdivision), tissue 1 "brain".
TetMesh kuhn_box(int n)
{
    TetMesh mesh;
    const double h = 20.0 / n;
    const auto index = [n](int i, int j, int k) { return static_cast<std::uint32_t>((k * (n + 1) + j) * (n + 1) + i); };
    for (int k = 0; k <= n; ++k)
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) mesh.vertices.push_back({i * h, j * h, k * h});
    const int orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                for (const auto& order : orders) {
                    int c[3] = {i, j, k};
                    Tet tet{index(i, j, k), 0, 0, 0};
                    for (int s = 0; s < 3; ++s) {
                        ++c[order[s]];
                        tet[s + 1] = index(c[0], c[1], c[2]);
                    }
                    mesh.tets.push_back(tet);
                    if (signed_volume(mesh, mesh.tets.size() - 1) < 0) std::swap(mesh.tets.back()[2], mesh.tets.back()[3]);
                    mesh.tet_labels.push_back(1);
                }
    mesh.names = {{0, "background"}, {1, "brain"}};
    return mesh;
}

/// tm-solve with 2 mA between two electrodes covering the faces x = 0 and x = 20 mm, on 2 processes, with the
/// Open MPI parameter file `parameters` (which names the host file).
CliResult solve_with(const TempDir& dir, const fs::path& parameters, const std::string& name)
{
    // Centres 200 mm behind the faces; the radius reaches the whole face and nothing else.
    const std::string radius = std::to_string(std::sqrt(200.0 * 200.0 + 200.0) + 1e-6);
    return run_program("env", {"OMPI_MCA_mca_base_param_files=" + parameters.string(), TM_TOOLS_DIR "/tm-solve", "-i",
                               (dir / "box.msh").string(), "-o", (dir / (name + ".vtu")).string(), "--processes", "2",
                               "--electrode", "-200,10,10," + radius + ",0.002", "--electrode", "220,10,10," + radius + ",-0.002",
                               "--json", (dir / (name + ".json")).string()});
}

TEST(SolveHostfileCli, RunsOnTheSlotsOfAnMpiHostFile)
{
    TempDir dir;
    io::write_tet_mesh(kuhn_box(58), dir / "box.msh", {.binary = true});
    std::ofstream(dir / "hosts") << "localhost slots=2\n";
    std::ofstream(dir / "mpi.conf") << "orte_default_hostfile = " << (dir / "hosts").string() << "\n";
    std::ofstream(dir / "unknown-hosts") << "no-such-node.invalid slots=2\n";
    std::ofstream(dir / "unknown.conf") << "orte_default_hostfile = " << (dir / "unknown-hosts").string() << "\n";

    CliResult result = solve_with(dir, dir / "mpi.conf", "two");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(result.err.find("warning"), std::string::npos) << result.err;
    nlohmann::json summary = read_json(dir / "two.json");
    EXPECT_EQ(summary["nodes"], 205379);
    EXPECT_EQ(summary["processes"], 2);
    EXPECT_LE(summary["relative_residual"].get<double>(), 1e-9);
    // J = 2e-3 A / 4e-4 m^2 = 5 A/m^2 in every tet (1e-6: the CG tolerance of 1e-10 on a 1.2 M-tet mesh).
    EXPECT_NEAR(summary["tissues"]["1"]["mean_J_A_per_m2"].get<double>(), 5.0, 1e-6);

    // The host file is what mpiexec used: one naming an unknown node fails, and tm-solve says so and solves alone.
    result = solve_with(dir, dir / "unknown.conf", "one");
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE(result.err.find("AMG-CG on 2 processes failed (mpiexec exited with status"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("solving in one process instead"), std::string::npos) << result.err;
    summary = read_json(dir / "one.json");
    EXPECT_EQ(summary["processes"], 1);
    EXPECT_NEAR(summary["tissues"]["1"]["mean_J_A_per_m2"].get<double>(), 5.0, 1e-6);
}

} // namespace
} // namespace tissuemesh::testing

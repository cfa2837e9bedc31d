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
#include "tests/fem/fem_meshes.h"
#include "tests/support/cli.h"

namespace tissuemesh::testing {
namespace {

namespace fs = std::filesystem;

// [0, 20]^3 mm, n^3 cubes of 6 tets (Kuhn subdivision), tissue 1 "brain".
TetMesh kuhn_box(int n)
{
    TetMesh mesh = box_mesh(n, 20.0);
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
                               "--electrode", "-200,10,10," + radius + ",0.002", "--electrode",
                               "220,10,10," + radius + ",-0.002", "--json", (dir / (name + ".json")).string()});
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
    EXPECT_NE(result.err.find("AMG-CG on 2 processes failed (mpiexec exited with status"), std::string::npos)
        << result.err;
    EXPECT_NE(result.err.find("solving in one process instead"), std::string::npos) << result.err;
    summary = read_json(dir / "one.json");
    EXPECT_EQ(summary["processes"], 1);
    EXPECT_NEAR(summary["tissues"]["1"]["mean_J_A_per_m2"].get<double>(), 5.0, 1e-6);
}

} // namespace
} // namespace tissuemesh::testing

// tm-solve as a user runs it: a box of "brain" with two face electrodes, whose exact potential is linear.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <utility>

#include "io/tet_mesh_io.h"
#include "tests/fem/fem_meshes.h"
#include "tests/support/cli.h"

namespace tissuemesh::testing {
namespace {

// [0, 20]^3 mm, 4^3 cubes of 6 tets (Kuhn subdivision), tissue 1 "brain".
TetMesh brain_box()
{
    TetMesh mesh = box_mesh(4, 20.0);
    mesh.names = {{0, "background"}, {1, "brain"}};
    return mesh;
}

void write(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

TEST(SolveCli, ElectrodesOnABoxGiveTheOhmicDrop)
{
    TempDir dir;
    io::write_tet_mesh(brain_box(), dir / "box.msh");
    write(dir / "cond.json", "{\"brain\": 0.5}");
    write(dir / "sensors.csv", "x,y,z\n0,10,10\n20,10,10\n");
    // Centres 200 mm behind the faces x = 0 and x = 20; the radius reaches the whole face and nothing else.
    const std::string radius = std::to_string(std::sqrt(200.0 * 200.0 + 200.0) + 1e-6);
    const CliResult result =
        run_cli("tm-solve",
                {"-i", (dir / "box.msh").string(), "-o", (dir / "out.vtu").string(), "--conductivity",
                 (dir / "cond.json").string(), "--electrode", "-200,10,10," + radius + ",0.002", "--electrode",
                 "220,10,10," + radius + ",-0.002", "--sensors", (dir / "sensors.csv").string(), "--sensor-potentials",
                 (dir / "eeg.csv").string(), "--error-indicator", "--json", (dir / "summary.json").string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const nlohmann::json summary = read_json(dir / "summary.json");
    EXPECT_EQ(summary["nodes"], 125);
    EXPECT_GT(summary["iterations"].get<int>(), 0);
    EXPECT_EQ(summary["processes"], 1); // --processes 0 (one per core), but 125 nodes are too few to share
    EXPECT_NEAR(summary["min_dihedral_deg"].get<double>(), 45.0, 1e-6); // Kuhn tets: dihedrals 45, 60, 90 deg
    EXPECT_LE(summary["relative_residual"].get<double>(), 1e-9);
    // J = 2e-3 A / 4e-4 m^2 = 5 A/m^2 everywhere, E = 10 V/m (1e-9: round-off).
    EXPECT_NEAR(summary["tissues"]["1"]["mean_J_A_per_m2"].get<double>(), 5.0, 1e-9);
    EXPECT_NEAR(summary["tissues"]["1"]["max_E_V_per_m"].get<double>(), 10.0, 1e-9);
    std::ifstream eeg(dir / "eeg.csv");
    std::stringstream text;
    text << eeg.rdbuf();
    // Drop I L / (sigma A) = 0.2 V, centred on zero (zero mean, symmetric grid): +0.1 V and -0.1 V.
    double x = 0, y = 0, z = 0, first = 0, second = 0;
    char comma = 0;
    std::string header;
    std::getline(text, header);
    EXPECT_EQ(header, "x,y,z,potential");
    text >> x >> comma >> y >> comma >> z >> comma >> first >> x >> comma >> y >> comma >> z >> comma >> second;
    EXPECT_NEAR(first, 0.1, 1e-9);
    EXPECT_NEAR(second, -0.1, 1e-9);
    std::ifstream vtu(dir / "out.vtu");
    std::stringstream vtu_text;
    vtu_text << vtu.rdbuf();
    for (const char* array : {"potential_V", "E_V_per_m", "J_A_per_m2", "error_indicator"})
        EXPECT_NE(vtu_text.str().find(std::string("Name=\"") + array + "\""), std::string::npos) << array;
    // The exact solution is linear: no flux jumps, the indicator is round-off (fields of 10 V/m).
    EXPECT_LT(summary["error_indicator_total"].get<double>(), 1e-10);
}

// The same two electrodes, one from a montage file with names and one as a flag: the same drop, and the named
// sensors keep their names in the output.
TEST(SolveCli, MontageFileAndFlagsAddUp)
{
    TempDir dir;
    io::write_tet_mesh(brain_box(), dir / "box.msh");
    const std::string radius = std::to_string(std::sqrt(200.0 * 200.0 + 200.0) + 1e-6);
    write(dir / "montage.csv",
          "# anode only; the cathode is a flag\nname,x,y,z,radius_mm,current_a\nanode,-200,10,10," + radius +
              ",+0.002\n");
    write(dir / "sensors.csv", "x,y,z,name\n0,10,10,left\n20,10,10,right\n");
    write(dir / "cond.json", "{\"brain\": 0.5}");
    const CliResult solved = run_cli(
        "tm-solve", {"-i", (dir / "box.msh").string(), "-o", (dir / "out.vtu").string(), "--conductivity",
                     (dir / "cond.json").string(), "--electrodes", (dir / "montage.csv").string(), "--electrode",
                     "220,10,10," + radius + ",-0.002", "--sensors", (dir / "sensors.csv").string(),
                     "--sensor-potentials", (dir / "eeg.csv").string(), "--json", (dir / "summary.json").string()});
    ASSERT_EQ(solved.exit_code, 0) << solved.err;
    EXPECT_EQ(read_json(dir / "summary.json")["electrode_nodes"].size(), 2u);
    std::ifstream eeg(dir / "eeg.csv");
    std::string header, left, right;
    std::getline(eeg, header);
    std::getline(eeg, left);
    std::getline(eeg, right);
    EXPECT_EQ(header, "name,x,y,z,potential");
    // Drop I L / (sigma A) = 0.2 V centred on zero, as with two flags (1e-9: round-off).
    ASSERT_TRUE(left.starts_with("left,0,10,10,")) << left;
    ASSERT_TRUE(right.starts_with("right,20,10,10,")) << right;
    EXPECT_NEAR(std::stod(left.substr(left.rfind(',') + 1)), 0.1, 1e-9);
    EXPECT_NEAR(std::stod(right.substr(right.rfind(',') + 1)), -0.1, 1e-9);
}

std::string read_file(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

TEST(SolveCli, SameBytesOnEveryRun)
{
    TempDir dir;
    io::write_tet_mesh(brain_box(), dir / "box.msh");
    // One and two OpenMP threads: assembly, fields and the indicator sum in a fixed order.
    for (const auto& [name, threads] : {std::pair{"a.vtu", "1"}, std::pair{"b.vtu", "2"}}) {
        setenv("OMP_NUM_THREADS", threads, 1);
        const CliResult result =
            run_cli("tm-solve", {"-i", (dir / "box.msh").string(), "-o", (dir / name).string(), "--dipole",
                                 "10,10,10,0,0,1e-8", "--dipole", "7,12,9,1e-8,0,0", "--error-indicator"});
        unsetenv("OMP_NUM_THREADS");
        ASSERT_EQ(result.exit_code, 0) << result.err;
    }
    const std::string first = read_file(dir / "a.vtu");
    EXPECT_GT(first.size(), 1000u);
    EXPECT_EQ(first, read_file(dir / "b.vtu"));
}

TEST(SolveCli, ErrorIndicatorAndPhaseTimesInTheSummary)
{
    TempDir dir;
    io::write_tet_mesh(brain_box(), dir / "box.msh");
    const CliResult result =
        run_cli("tm-solve", {"-i", (dir / "box.msh").string(), "-o", (dir / "out.vtu").string(), "--dipole",
                             "10,10,10,0,0,1e-8", "--json", (dir / "summary.json").string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    // Without --error-indicator the indicator is neither computed nor written.
    EXPECT_EQ(read_file(dir / "out.vtu").find("Name=\"error_indicator\""), std::string::npos);
    const nlohmann::json summary = read_json(dir / "summary.json");
    EXPECT_FALSE(summary.contains("error_indicator_total"));
    // The iterations go next to the smallest dihedral angle (slivers slow CG down).
    EXPECT_GT(summary["iterations"].get<int>(), 0);
    EXPECT_TRUE(summary.contains("min_dihedral_deg"));
    for (const char* phase : {"read", "assembly", "solver_setup", "solver_iterations", "fields", "write"})
        EXPECT_GE(summary["phase_seconds"][phase].get<double>(), 0.0) << phase;
}

// The box is symmetric under the inversion x -> (20, 20, 20) - x (each cube's six tets run along its
// diagonal both ways), and a dipole at the centre node turns into its negative under it: the potential is
// odd. Venant's monopoles on the centre node's star keep that symmetry; subtraction refuses a dipole on a
// node and says what to use instead.
TEST(SolveCli, VenantDipoleOnTheCentreNodeGivesAnOddPotential)
{
    TempDir dir;
    io::write_tet_mesh(brain_box(), dir / "box.msh");
    write(dir / "sensors.csv", "x,y,z\n0,10,10\n20,10,10\n10,0,10\n10,20,10\n");
    CliResult result =
        run_cli("tm-solve", {"-i", (dir / "box.msh").string(), "-o", (dir / "out.vtu").string(), "--dipole",
                             "10,10,10,1e-8,0,0", "--dipole-model", "venant", "--sensors",
                             (dir / "sensors.csv").string(), "--sensor-potentials", (dir / "eeg.csv").string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    std::stringstream text(read_file(dir / "eeg.csv"));
    std::string line;
    std::getline(text, line);
    std::vector<double> potential;
    while (std::getline(text, line)) potential.push_back(std::stod(line.substr(line.rfind(',') + 1)));
    ASSERT_EQ(potential.size(), 4u);
    // x = 0 is behind the dipole (pointing to +x), x = 20 ahead of it; y = 0 and y = 20 are mirror images
    // of each other under the inversion, so they are opposite too (the 1e-8 relative: the CG tolerance).
    EXPECT_LT(potential[0], 0.0);
    EXPECT_NEAR(potential[0], -potential[1], 1e-8 * std::abs(potential[0]));
    EXPECT_NEAR(potential[2], -potential[3], 1e-8 * std::abs(potential[0]));
    result = run_cli("tm-solve", {"-i", (dir / "box.msh").string(), "-o", (dir / "sub.vtu").string(), "--dipole",
                                  "10,10,10,1e-8,0,0", "--dipole-model", "subtraction"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("lies on a mesh node"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("use the Venant model"), std::string::npos) << result.err;
    result = run_cli("tm-solve", {"--help"});
    EXPECT_EQ(result.exit_code, 0);
    EXPECT_NE(result.out.find("venant"), std::string::npos) << result.out;
}

TEST(SolveCli, BadInputExitsTwoWithTheReason)
{
    TempDir dir;
    io::write_tet_mesh(brain_box(), dir / "box.msh");
    write(dir / "cond.json", "{\"skull\": 0.01}");
    CliResult result = run_cli("tm-solve", {"-i", (dir / "box.msh").string(), "-o", (dir / "out.vtu").string(),
                                            "--conductivity", (dir / "cond.json").string()});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("'skull' is no tissue of the mesh"), std::string::npos) << result.err;
    result = run_cli("tm-solve", {"-i", (dir / "box.msh").string(), "-o", (dir / "out.vtu").string(), "--dipole",
                                  "10,10,10,0,1e-8"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("has 5 numbers, not 6"), std::string::npos) << result.err;
    result = run_cli("tm-solve", {"-i", (dir / "box.msh").string(), "-o", (dir / "out.vtu").string(), "--dipole",
                                  "10,10,30,0,0,1e-8"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("lies outside the mesh"), std::string::npos) << result.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.vtu"));
}

} // namespace
} // namespace tissuemesh::testing

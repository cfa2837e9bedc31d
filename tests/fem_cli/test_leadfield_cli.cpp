// tm-leadfield as users run it: EEG, MEG and tDCS lead fields with their sidecars, tm-solve summing a montage
// from the tDCS lead field, bad input refused with one line and no output, and MNE-Python localising a dipole
// with our EEG lead field.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "core/error.h"
#include "io/npy.h"
#include "io/read_vtu.h"
#include "io/tet_mesh_io.h"
#include "tests/fem/fem_meshes.h"
#include "tests/support/cli.h"

namespace tissuemesh::testing {
namespace {

void write(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

// n electrodes spread over the upper part of the sphere of `radius_mm`, named E1..En.
std::string electrode_csv(int n, double radius_mm)
{
    std::string csv = "name,x,y,z\n";
    const double golden = std::numbers::pi * (3 - std::sqrt(5.0));
    for (int k = 0; k < n; ++k) {
        const double z = 1 - (k + 0.5) / n * 1.3, r = std::sqrt(1 - z * z);
        csv += concat("E", k + 1, ",", radius_mm * r * std::cos(golden * k), ",", radius_mm * r * std::sin(golden * k),
                      ",", radius_mm * z, "\n");
    }
    return csv;
}

// A small 4-shell head (icosphere level 3, tissues scalp, skull, csf, brain) in a folder with a cap of 16
// electrodes, 3 free sources and 4 MEG sensors (3 magnetometers, 1 gradiometer).
struct HeadFolder {
    TempDir dir;
    std::string mesh = (dir / "head.msh").string();
    explicit HeadFolder(int levels = 3, double max_volume_mm3 = 30.0)
    {
        io::write_tet_mesh(four_shell_head(levels, max_volume_mm3), mesh);
        write(dir / "eeg.csv", electrode_csv(16, 92.3));
        write(dir / "src.csv", "x,y,z\n3.1,-7.2,20.4\n-30.3,41.7,33.9\n10.2,5.6,60.8\n");
        write(dir / "meg.csv", "name,x,y,z,nx,ny,nz,x2,y2,z2\nM1,0,0,102,0,0,1,,,\nM2,0,102,0,1,0,0,,,\n"
                               "M3,-60,60,55,0,0.6,0.8,,,\nG1,72.1,0,72.1,1,0,1,93.3,0,93.3\n");
    }
    std::string path(const std::string& name) const { return (dir / name).string(); }
};

TEST(LeadfieldCli, WritesEegAndMegLeadFieldsWithSidecars)
{
    const HeadFolder head;
    const CliResult result =
        run_cli("tm-leadfield", {"-i", head.mesh, "--sensors", head.path("eeg.csv"), "--sources", head.path("src.csv"),
                                 "-o", head.path("eeg.npy"), "--meg-sensors", head.path("meg.csv"), "--meg-output",
                                 head.path("meg.npy"), "--json", head.path("run.json")});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const io::NpyMatrix eeg = io::read_npy(head.path("eeg.npy")), meg = io::read_npy(head.path("meg.npy"));
    ASSERT_EQ(eeg.rows, 16u);
    ASSERT_EQ(eeg.columns, 9u);
    ASSERT_EQ(meg.rows, 4u);
    ASSERT_EQ(meg.columns, 9u);
    for (std::size_t c = 0; c < 9; ++c) { // average reference: every column sums to zero
        double sum = 0, size = 0;
        for (std::size_t r = 0; r < 16; ++r) sum += eeg.values[r * 9 + c], size += std::abs(eeg.values[r * 9 + c]);
        EXPECT_LT(std::abs(sum), 1e-12 * size);
        EXPECT_GT(size, 0);
    }
    const nlohmann::json sidecar = read_json(head.path("eeg.json"));
    EXPECT_EQ(sidecar["kind"], "eeg");
    EXPECT_EQ(sidecar["units"], "V per A*m");
    EXPECT_EQ(sidecar["reference"], "average");
    EXPECT_EQ(sidecar["dipole_model"], "venant");
    EXPECT_EQ(sidecar["sensors"].size(), 16u);
    EXPECT_EQ(sidecar["sensors"][3]["name"], "E4");
    EXPECT_LT(sidecar["sensors"][3]["distance_mm"].get<double>(), 1.0);
    EXPECT_EQ(sidecar["sources"].size(), 3u);
    EXPECT_EQ(sidecar["sources"][2]["first_column"], 6);
    EXPECT_EQ(sidecar["sources"][2]["tissue"], 4);
    EXPECT_EQ(sidecar["mesh"]["fingerprint"].get<std::string>().size(), 16u);
    EXPECT_EQ(sidecar["conductivities"]["skull"], 0.01);
    const nlohmann::json meg_sidecar = read_json(head.path("meg.json"));
    EXPECT_EQ(meg_sidecar["units"], "T per A*m");
    EXPECT_EQ(meg_sidecar["sensors"][3]["second_coil_mm"][0], 93.3);
    const nlohmann::json run = read_json(head.path("run.json"));
    EXPECT_EQ(run["solves"], 15 + 4);
    EXPECT_EQ(run["columns"], 9);
    EXPECT_LE(run["relative_residual_max"].get<double>(),
              1e-5); // 10 x the default tolerance, as solve_spd_columns allows
    EXPECT_NE(result.err.find("solves done"), std::string::npos) << result.err; // progress: 19 solves, a line per tenth
}

// The tDCS lead field of a 4-electrode cap, then tm-solve sums two montages from it: the potentials equal
// tm-solve's own solves of those montages (both to 1e-12: differences of 1e-9 of the range allowed).
TEST(LeadfieldCli, TmSolveSumsAMontageFromTheTdcsLeadField)
{
    const HeadFolder head;
    write(head.dir / "cap.csv", "name,x,y,z,radius_mm\nT7,-92,0,0,15\nT8,92,0,0,15\nCz,0,0,92,15\nFpz,0,92,0,20\n");
    const CliResult built =
        run_cli("tm-leadfield", {"-i", head.mesh, "--tdcs-electrodes", head.path("cap.csv"), "--tdcs-reference", "Cz",
                                 "--tdcs-output", head.path("tdcs.npy"), "--tolerance", "1e-12"});
    ASSERT_EQ(built.exit_code, 0) << built.err;
    EXPECT_EQ(read_json(head.path("tdcs.json"))["reference"], "Cz");
    for (const char* montage :
         {"name,x,y,z,radius_mm,current_a\nT7,-92,0,0,15,1e-3\nT8,92,0,0,15,-1e-3\n",
          "name,x,y,z,radius_mm,current_a\nFpz,0,92,0,20,2e-3\nCz,0,0,92,15,-1.5e-3\nT8,92,0,0,15,-0.5e-3\n"}) {
        write(head.dir / "montage.csv", montage);
        const CliResult summed = run_cli("tm-solve", {"-i", head.mesh, "-o", head.path("summed.vtu"), "--leadfield",
                                                      head.path("tdcs.npy"), "--electrodes", head.path("montage.csv")});
        ASSERT_EQ(summed.exit_code, 0) << summed.err;
        const CliResult direct =
            run_cli("tm-solve", {"-i", head.mesh, "-o", head.path("direct.vtu"), "--electrodes",
                                 head.path("montage.csv"), "--tolerance", "1e-12", "--processes", "1"});
        ASSERT_EQ(direct.exit_code, 0) << direct.err;
        const std::vector<double> a = io::read_vtu(head.path("summed.vtu")).point_array("potential_V")->values;
        const std::vector<double> b = io::read_vtu(head.path("direct.vtu")).point_array("potential_V")->values;
        ASSERT_EQ(a.size(), b.size());
        const auto [low, high] = std::minmax_element(b.begin(), b.end());
        double worst = 0;
        for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
        EXPECT_LT(worst, 1e-9 * (*high - *low));
    }
}

// Each bad input: exit 2, one line on stderr naming the item, and no output file.
TEST(LeadfieldCli, BadInputExitsTwoWithOneLineAndNoOutput)
{
    const HeadFolder head;
    write(head.dir / "off.csv", electrode_csv(4, 92.3) + "Fz,0,0,150\n");
    write(head.dir / "outside.csv", "x,y,z\n0,0,10\n0,0,95\n");
    write(head.dir / "skull.csv", "x,y,z\n0,0,10\n0,0,83\n");
    write(head.dir / "inside.csv", "name,x,y,z,nx,ny,nz\nMEG0111,0,0,50,0,0,1\n");
    write(head.dir / "bad.npy", "\x93NUMPY\x01\x00\x10\x00{'descr'");
    write(head.dir / "cap.csv", "name,x,y,z,radius_mm\nT7,-92,0,0,15\nT8,92,0,0,15\n");
    write(head.dir / "montage.csv", "name,x,y,z,radius_mm,current_a\nT7,-92,0,0,15,1e-3\nC3,-60,0,60,15,-1e-3\n");
    const std::string mesh = head.mesh, eeg = head.path("eeg.csv"), src = head.path("src.csv"),
                      out = head.path("out.npy");
    struct Case {
        std::vector<std::string> args;
        std::string expected;
    };
    const std::vector<Case> cases{
        {{"-i", mesh, "--sensors", head.path("off.csv"), "--sources", src, "-o", out},
         "Fz (" + head.path("off.csv") + " line 6) at (0, 0, 150) mm is 58"},
        {{"-i", mesh, "--sensors", eeg, "--sources", head.path("outside.csv"), "-o", out},
         "source 2 (" + head.path("outside.csv") + " line 3) at (0, 0, 95) mm lies outside the mesh"},
        {{"-i", mesh, "--sensors", eeg, "--sources", head.path("skull.csv"), "--source-tissues", "brain,csf", "-o",
          out},
         "line 3) at (0, 0, 83) mm lies in skull (2), not in the source tissues (brain (4), csf (3))"},
        {{"-i", mesh, "--meg-sensors", head.path("inside.csv"), "--sources", src, "--meg-output", out},
         "MEG0111 (" + head.path("inside.csv") + " line 2) has a coil at (0, 0, 50) mm inside the head"},
        {{"-i", mesh, "--sensors", eeg, "--source-grid-mm", "10", "--source-tissues", "gray_matter", "-o", out},
         "--source-tissues: unknown tissue \"gray_matter\"; the tissues of " + mesh +
             " are 1 scalp, 2 skull, 3 csf, 4 brain"},
        {{"-i", mesh, "--sensors", eeg, "-o", out}, "the EEG and MEG lead fields need sources"},
        {{"-i", mesh, "--sensors", eeg, "--sources", src, "-o", out, "--reference", "Cz"},
         "--reference Cz: no electrode of"},
        {{"-i", mesh, "--tdcs-electrodes", head.path("cap.csv"), "--tdcs-output", out, "--tdcs-reference", "Oz"},
         "--tdcs-reference Oz"},
    };
    for (const Case& c : cases) {
        const CliResult result = run_cli("tm-leadfield", c.args);
        EXPECT_EQ(result.exit_code, 2) << c.expected;
        EXPECT_NE(result.err.find(c.expected), std::string::npos) << result.err;
        EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << c.expected;
        EXPECT_FALSE(std::filesystem::exists(head.path("out.json"))) << c.expected;
    }
    // tm-solve --leadfield: a damaged .npy, and a montage electrode the lead field does not have.
    ASSERT_EQ(run_cli("tm-leadfield",
                      {"-i", mesh, "--tdcs-electrodes", head.path("cap.csv"), "--tdcs-output", head.path("tdcs.npy")})
                  .exit_code,
              0);
    std::filesystem::copy_file(head.path("tdcs.json"), head.path("bad.json"));
    for (const auto& [lead_field, expected] :
         {std::pair{head.path("bad.npy"), std::string("bad.npy")},
          std::pair{head.path("tdcs.npy"),
                    "C3 (" + head.path("montage.csv") + " line 3): not an electrode of the lead field"}}) {
        const CliResult result = run_cli("tm-solve", {"-i", mesh, "-o", head.path("sum.vtu"), "--leadfield", lead_field,
                                                      "--electrodes", head.path("montage.csv")});
        EXPECT_EQ(result.exit_code, 2);
        EXPECT_NE(result.err.find(expected), std::string::npos) << result.err;
        EXPECT_FALSE(std::filesystem::exists(head.path("sum.vtu")));
    }
}

// MNE-Python 1.3 (Debian's python3-mne) takes our EEG lead field as an mne.Forward (python/examples/mne_forward.py)
// and its eLORETA localises dipoles simulated with MNE's own 4-shell sphere model: 64 electrodes, a 7 mm grid in
// the brain (4 697 sources), dipoles 1.4-1.7 mm from a grid point. Measured: each peak on that nearest grid
// point (errors 1.39, 1.73, 1.63 mm); our columns there against MNE's sphere model RDM 0.004-0.021.
TEST(LeadfieldCli, MneLocalisesDipolesWithOurLeadField)
{
    const HeadFolder head;
    write(head.dir / "cap.csv", electrode_csv(64, 92.3));
    const CliResult built =
        run_cli("tm-leadfield",
                {"-i", head.mesh, "--sensors", head.path("cap.csv"), "--source-grid-mm", "7", "--source-tissues",
                 "brain", "--source-min-distance-mm", "5", "-o", head.path("eeg.npy"), "-q"});
    ASSERT_EQ(built.exit_code, 0) << built.err;
    const CliResult mne =
        run_program("/usr/bin/python3", {data_path("../python/examples/mne_forward.py").string(), head.path("eeg.npy"),
                                         "--dipole=21.8,-7.9,48.3,3e-8,0,4e-8", "--dipole=-33.9,15.2,-7.6,0,2e-8,1e-8",
                                         "--dipole=6.2,48.1,36.1,-1e-8,1e-8,3e-8"});
    ASSERT_EQ(mne.exit_code, 0) << mne.err;
    const nlohmann::json result = nlohmann::json::parse(mne.out);
    EXPECT_EQ(result["channels"], 64);
    EXPECT_GT(result["sources"].get<int>(), 4000);
    ASSERT_EQ(result["dipoles"].size(), 3u);
    for (const nlohmann::json& dipole : result["dipoles"]) {
        EXPECT_LE(dipole["error_mm"].get<double>(), 5.0) << dipole.dump();
        for (const nlohmann::json& rdm : dipole["rdm_at_peak_vs_mne_sphere"])
            EXPECT_LT(rdm.get<double>(), 0.05) << dipole.dump();
    }
}

} // namespace
} // namespace tissuemesh::testing

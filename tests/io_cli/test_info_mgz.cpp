// tm-info on a FreeSurfer .mgz equals tm-info on the same image as NIfTI (both written by nibabel): counts, spacing,
// the world bounds of the voxels (their outer corners), per tissue too; a FreeSurfer colour table names the tissues;
// a truncated .mgz is refused with one line and exit 2.
#include <algorithm>
#include <fstream>
#include <gtest/gtest.h>

#include "core/atomic_file.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

// An aseg-like image: 0 background, 2/41 white matter, 3/42 cortex, 24 CSF; the affine of FreeSurfer's conformed
// space at 1.5 mm (LIA: i to left, j to inferior, k to anterior), exact in float32.
const char* const write_script = R"PY(
import sys
import numpy as np
import nibabel as nib
folder = sys.argv[1]
i, j, k = np.meshgrid(np.arange(12), np.arange(10), np.arange(8), indexing="ij")
aseg = np.zeros((12, 10, 8), np.int32)
aseg[2:10, 2:8, 1:7] = 24
aseg[3:9, 3:7, 2:6] = np.where(i[3:9, 3:7, 2:6] < 6, 3, 42)
aseg[4:8, 4:6, 3:5] = np.where(i[4:8, 4:6, 3:5] < 6, 2, 41)
affine = np.array([[-1.5, 0, 0, 9.0], [0, 0, 1.5, -6.0], [0, -1.5, 0, 7.5], [0, 0, 0, 1]])
nib.save(nib.MGHImage(aseg, affine), folder + "/aseg.mgz")
nib.save(nib.Nifti1Image(aseg.astype(np.int16), affine), folder + "/aseg.nii.gz")
)PY";

TEST(InfoMgz, EqualsInfoOnTheSameImageAsNifti)
{
    testing::TempDir dir;
    std::ofstream(dir / "write.py") << write_script;
    const testing::CliResult made =
        testing::run_program("/usr/bin/python3", {(dir / "write.py").string(), dir.path().string()});
    ASSERT_EQ(made.exit_code, 0) << made.err;
    std::ofstream(dir / "FreeSurferColorLUT.txt")
        << "#No. Label Name:                R   G   B   A\n0   Unknown  0 0 0 0\n"
           "2   Left-Cerebral-White-Matter  245 245 245 0\n3   Left-Cerebral-Cortex  205 62 78 0\n"
           "24  CSF  60 60 60 0\n41  Right-Cerebral-White-Matter  0 225 0 0\n"
           "42  Right-Cerebral-Cortex  205 62 78 0\n";
    for (const char* name : {"aseg.mgz", "aseg.nii.gz"}) {
        const testing::CliResult info =
            testing::run_cli("tm-info", {(dir / name).string(), "--labels", (dir / "FreeSurferColorLUT.txt").string(),
                                         "--json", (dir / (std::string(name) + ".json")).string()});
        ASSERT_EQ(info.exit_code, 0) << info.err;
    }
    const nlohmann::json mgz = testing::read_json(dir / "aseg.mgz.json"),
                         nifti = testing::read_json(dir / "aseg.nii.gz.json");
    EXPECT_EQ(mgz["dims"], nifti["dims"]);
    EXPECT_EQ(mgz["voxel_counts"], nifti["voxel_counts"]);
    EXPECT_EQ(mgz["voxel_counts"].size(), 6u);
    EXPECT_EQ(mgz["spacing_mm"], nifti["spacing_mm"]);
    EXPECT_EQ(mgz["orientation"], nifti["orientation"]);
    auto near = [](const nlohmann::json& a, const nlohmann::json& b, const std::string& what) {
        ASSERT_EQ(a.size(), b.size()) << what;
        for (std::size_t c = 0; c < a.size(); ++c)
            EXPECT_NEAR(a[c].get<double>(), b[c].get<double>(), 1e-9) << what << " " << c;
    };
    near(mgz["bounds_mm"][0], nifti["bounds_mm"][0], "bounds min");
    near(mgz["bounds_mm"][1], nifti["bounds_mm"][1], "bounds max");
    near(mgz["origin_mm"], nifti["origin_mm"], "origin");
    near(mgz["direction"], nifti["direction"], "direction");
    ASSERT_EQ(mgz["labels"].size(), nifti["labels"].size());
    for (std::size_t l = 0; l < mgz["labels"].size(); ++l) {
        const nlohmann::json &a = mgz["labels"][l], &b = nifti["labels"][l];
        EXPECT_EQ(a["name"], b["name"]);
        EXPECT_EQ(a["components26"], b["components26"]);
        near(a["bbox_mm_min"], b["bbox_mm_min"], "tissue box min");
        near(a["bbox_mm_max"], b["bbox_mm_max"], "tissue box max");
    }
    EXPECT_EQ(mgz["labels"][3]["name"], "CSF");
    EXPECT_EQ(mgz["labels"][5]["name"], "Right-Cerebral-Cortex");
    // From the affine by hand: x = 9 - 1.5 i, y = -6 + 1.5 k, z = 7.5 - 1.5 j over the outer corners (index -0.5
    // and n - 0.5) of the 12 x 10 x 8 voxels.
    near(mgz["bounds_mm"][0], nlohmann::json::array({-8.25, -6.75, -6.75}), "bounds min by hand");
    near(mgz["bounds_mm"][1], nlohmann::json::array({9.75, 5.25, 8.25}), "bounds max by hand");
}

TEST(InfoMgz, TruncatedMgzIsRefusedWithOneLine)
{
    testing::TempDir dir;
    std::ofstream(dir / "write.py") << write_script;
    ASSERT_EQ(testing::run_program("/usr/bin/python3", {(dir / "write.py").string(), dir.path().string()}).exit_code,
              0);
    // Cut the (uncompressed) .mgh: the header promises more voxels than the file holds.
    const std::string bytes = read_file_bytes(dir / "aseg.mgz");
    std::ofstream(dir / "cut.mgz", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    const testing::CliResult info = testing::run_cli("tm-info", {(dir / "cut.mgz").string()});
    EXPECT_EQ(info.exit_code, 2);
    EXPECT_NE(info.err.find("cut.mgz"), std::string::npos) << info.err;
    EXPECT_EQ(std::count(info.err.begin(), info.err.end(), '\n'), 1) << info.err;
}

} // namespace
} // namespace tissuemesh

// nibabel (Debian's python3-nibabel) writes .mgz, .mgh and .nii.gz files of one label image under an oblique
// affine; we read each and must put every voxel corner where nibabel's affine puts it, with the same labels.
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/read_label_image.h"
#include "tests/support/cli.h"

namespace tissuemesh::io {
namespace {

const char* const python = "/usr/bin/python3";

// Labels 0..5 in a 7 x 8 x 9 grid (x fastest), rotated 30 degrees about z and 10 about x, anisotropic spacing,
// off-centre; the affine printed is the one nibabel reads back from each file (MGH stores float32 fields).
const char* const write_script = R"PY(
import json, sys
import numpy as np
import nibabel as nib
folder = sys.argv[1]
i, j, k = np.meshgrid(np.arange(7), np.arange(8), np.arange(9), indexing="ij")
labels = ((i + 2 * j + 3 * k) % 6).astype(np.uint8)
a, b = np.radians(30), np.radians(10)
rz = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
rx = np.array([[1, 0, 0], [0, np.cos(b), -np.sin(b)], [0, np.sin(b), np.cos(b)]])
affine = np.eye(4)
affine[:3, :3] = rx @ rz @ np.diag([1.5, 0.75, 2.0])
affine[:3, 3] = [-31.2, 17.4, 5.9]
out = {}
for name, image in [("a.mgz", nib.MGHImage(labels, affine)), ("b.mgh", nib.MGHImage(labels.astype(np.int32), affine)),
                    ("c.nii.gz", nib.Nifti1Image(labels, affine))]:
    nib.save(image, folder + "/" + name)
    back = nib.load(folder + "/" + name)
    assert (np.asarray(back.dataobj) == labels).all()
    out[name] = back.affine.tolist()
print(json.dumps(out))
)PY";

TEST(WeReadNibabelFiles, MgzMghAndNiftiPutEveryVoxelCornerWhereNibabelDoes)
{
    testing::TempDir dir;
    std::ofstream(dir / "write.py") << write_script;
    const testing::CliResult result = testing::run_program(python, {(dir / "write.py").string(), dir.path().string()});
    ASSERT_EQ(result.exit_code, 0) << result.err
                                   << (result.exit_code == 127 ? " (python3 missing: run scripts/setup)" : "");
    const nlohmann::json affines = nlohmann::json::parse(result.out);
    for (const std::string name : {"a.mgz", "b.mgh", "c.nii.gz"}) {
        SCOPED_TRACE(name);
        const LabelImage image = read_label_image(dir / name);
        ASSERT_EQ(image.dims(), (Dims{7, 8, 9}));
        for (std::size_t k = 0; k < 9; ++k)
            for (std::size_t j = 0; j < 8; ++j)
                for (std::size_t i = 0; i < 7; ++i) ASSERT_EQ(image.at(i, j, k), (i + 2 * j + 3 * k) % 6);
        // nibabel's affine maps voxel centres (integer indices): the corners lie half a voxel out.
        const auto& m = affines.at(name);
        double worst = 0;
        for (const double ci : {-0.5, 6.5})
            for (const double cj : {-0.5, 7.5})
                for (const double ck : {-0.5, 8.5}) {
                    const Vec3 ours = image.index_to_world({ci, cj, ck});
                    for (std::size_t row = 0; row < 3; ++row) {
                        const double theirs = m[row][0].get<double>() * ci + m[row][1].get<double>() * cj +
                                              m[row][2].get<double>() * ck + m[row][3].get<double>();
                        worst = std::max(worst, std::abs(ours[row] - theirs));
                    }
                }
        EXPECT_LT(worst, 1e-5) << "mm; the header fields are float32, exact to about 1e-6 mm here";
    }
}

} // namespace
} // namespace tissuemesh::io

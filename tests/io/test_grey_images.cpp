// Grey-level images (CT, MRI values) for tm-snake --grey: every format the label reader takes through ITK
// (NIfTI-1, NRRD, MetaImage) and Inrimage, values as floats with NIfTI's scaling, geometry as for labels.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "io/read_grey_image.h"
#include "io/read_label_image.h"
#include "io/write_label_image.h"
#include "tests/io/expect_error.h"
#include "tests/io/make_test_images.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

using testing::expect_error;

TEST(GreyImages, NiftiIntegersAreScaledToFloats)
{
    // CT-style storage: int16 with slope 0.5 and intercept -1024, so odd stored values give halves.
    const testing::TempDir dir;
    testing::NiftiSpec spec;
    spec.datatype = 4;
    spec.bitpix = 16;
    spec.scale_slope = 0.5f;
    spec.scale_intercept = -1024;
    const std::vector<std::int16_t> stored{0, 1, 2, 3, 2048, 2049, 4095, -7};
    testing::write_nifti(dir.path() / "ct.nii", spec, testing::voxel_bytes(stored));
    const io::GreyImage grey = io::read_grey_image(dir.path() / "ct.nii");
    ASSERT_EQ(grey.values.size(), stored.size());
    for (std::size_t v = 0; v < stored.size(); ++v) EXPECT_EQ(grey.values[v], 0.5f * stored[v] - 1024) << "voxel " << v;
}

TEST(GreyImages, EveryItkFormatGivesTheLabelReadersGeometryAndValues)
{
    // An oriented, anisotropic image written as labels in each format, read back as grey values.
    const testing::TempDir dir;
    const LabelImage labels = testing::make_oriented_image(3);
    for (const std::string name : {"a.nii.gz", "a.nrrd", "a.mha", "a.nhdr", "a.mhd"}) {
        io::write_label_image(labels, dir.path() / name);
        const io::GreyImage grey = io::read_grey_image(dir.path() / name);
        ASSERT_EQ(grey.grid.dims(), labels.dims()) << name;
        for (std::size_t v = 0; v < labels.voxel_count(); ++v)
            ASSERT_EQ(grey.values[v], static_cast<float>(labels.labels()[v])) << name << " voxel " << v;
        const LabelImage again = io::read_label_image(dir.path() / name);
        for (const std::array<double, 3> index : {std::array<double, 3>{0, 0, 0}, {4, 3, 2}, {1.5, 0.5, 2}})
            for (int axis = 0; axis < 3; ++axis)
                EXPECT_NEAR(grey.grid.index_to_world(index)[axis], again.index_to_world(index)[axis], 1e-9) << name;
    }
}

TEST(GreyImages, BadFilesAreRefusedWithOneLine)
{
    const testing::TempDir dir;
    testing::NiftiSpec spec;
    spec.datatype = 16;
    spec.bitpix = 32;
    std::vector<float> values(8, 1.5f);
    values[5] = std::numeric_limits<float>::quiet_NaN();
    testing::write_nifti(dir.path() / "nan.nii", spec, testing::voxel_bytes(values));
    // niftilib (under ITK) reads non-finite NIfTI values as 0, as FSL and ITK tools do: not an error there.
    EXPECT_EQ(io::read_grey_image(dir.path() / "nan.nii").values[5], 0.0f);
    testing::write_nifti(dir.path() / "short.nii", spec, testing::voxel_bytes(std::vector<float>(3, 1.0f)));
    expect_error<IoError>([&] { io::read_grey_image(dir.path() / "short.nii"); }, {"short.nii", "truncated"});
    testing::write_nifti2(dir.path() / "two.nii", {2, 2, 2}, std::vector<unsigned char>(8, 1));
    expect_error<IoError>([&] { io::read_grey_image(dir.path() / "two.nii"); }, {"two.nii", "NIfTI-2", "NIfTI-1"});
    testing::write_bytes(dir.path() / "grey.png", {1, 2, 3});
    expect_error<IoError>([&] { io::read_grey_image(dir.path() / "grey.png"); }, {"grey.png", ".nii.gz"});
    testing::write_bytes(dir.path() / "empty.nii", {});
    expect_error<IoError>([&] { io::read_grey_image(dir.path() / "empty.nii"); }, {"empty.nii", "empty"});
}

} // namespace
} // namespace tissuemesh

// ReadImageOptions::before_voxels: every format calls it once, after the header checks and before any voxel
// is allocated, with the image's dimensions, spacing and stored bytes per voxel; what it throws ends the read.
// read_label_image_spacing() reads only that far.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "io/read_label_image.h"
#include "io/write_label_image.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

class BeforeVoxels : public ::testing::TestWithParam<std::string> {};

TEST_P(BeforeVoxels, SeesTheHeaderAndCanRefuseTheImage)
{
    testing::TempDir dir;
    const std::filesystem::path path = dir / ("image" + GetParam());
    // Identity orientation (Inrimage has no other), labels 0..25: stored as uint8 by every writer.
    LabelImage written({5, 4, 3}, {0.5, 1.25, 2.0}, {-10.5, 20.25, 3.0});
    for (std::size_t k = 0; k < 3; ++k)
        for (std::size_t j = 0; j < 4; ++j)
            for (std::size_t i = 0; i < 5; ++i) written.at(i, j, k) = static_cast<Label>(i + 2 * j + 7 * k);
    io::write_label_image(written, path);
    int calls = 0;
    Dims seen_dims{};
    Vec3 seen_spacing{};
    std::size_t seen_bytes = 0;
    const LabelImage image =
        io::read_label_image(path, {.before_voxels = [&](const Dims& dims, const Vec3& spacing, std::size_t bytes) {
                                 ++calls, seen_dims = dims, seen_spacing = spacing, seen_bytes = bytes;
                             }});
    EXPECT_EQ(calls, 1);
    EXPECT_EQ(seen_dims, image.dims());
    EXPECT_EQ(seen_dims, (Dims{5, 4, 3}));
    for (int axis = 0; axis < 3; ++axis)
        EXPECT_NEAR(seen_spacing[axis], image.spacing_mm()[axis], 1e-6) << axis; // float headers
    EXPECT_EQ(seen_bytes, 1u);
    try {
        (void)io::read_label_image(path, {.before_voxels = [](const Dims&, const Vec3&, std::size_t) {
                                       throw InputError("too big for this test");
                                   }});
        FAIL() << "the hook's refusal must end the read";
    } catch (const InputError& error) {
        EXPECT_STREQ(error.what(), "too big for this test");
    }
}

TEST_P(BeforeVoxels, GivesTheSpacingFromTheHeaderAlone)
{
    testing::TempDir dir;
    const std::filesystem::path path = dir / ("image" + GetParam());
    LabelImage written({5, 4, 3}, {0.5, 1.25, 2.0});
    written.at(1, 1, 1) = 3;
    io::write_label_image(written, path);
    const Vec3 spacing = io::read_label_image_spacing(path);
    for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(spacing[axis], written.spacing_mm()[axis], 1e-6) << axis;
    EXPECT_THROW((void)io::read_label_image_spacing(dir / "missing.nii.gz"), IoError);
}

std::string format_name(const ::testing::TestParamInfo<std::string>& format)
{
    std::string name = format.param.substr(1);
    for (char& c : name) c = c == '.' ? '_' : c;
    return name;
}

INSTANTIATE_TEST_SUITE_P(Formats, BeforeVoxels,
                         ::testing::Values(".nii", ".nii.gz", ".nrrd", ".mha", ".inr.gz", ".json"), format_name);

} // namespace
} // namespace tissuemesh

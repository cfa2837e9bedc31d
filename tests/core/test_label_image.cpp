#include <cmath>
#include <gtest/gtest.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/label_image.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

TEST(LabelImage, MapsIndicesToWorldWithSpacingOriginAndDirection)
{
    // Axes permuted and flipped: i -> -y, j -> +x, k -> +z.
    const Mat3 direction{0, 1, 0, -1, 0, 0, 0, 0, 1};
    const LabelImage image({4, 5, 6}, {0.5, 2.0, 3.0}, {10, 20, 30}, direction);
    const Vec3 world = image.index_to_world({1, 2, 3});
    EXPECT_DOUBLE_EQ(world[0], 10 + 2 * 2.0);
    EXPECT_DOUBLE_EQ(world[1], 20 - 1 * 0.5);
    EXPECT_DOUBLE_EQ(world[2], 30 + 3 * 3.0);
    const Vec3 back = image.world_to_index(world);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(back[a], (Vec3{1, 2, 3})[a], 1e-12);
}

TEST(LabelImage, WorldBoundsCoverWholeVoxels)
{
    const LabelImage image({2, 3, 4}, {1, 1, 2});
    const auto bounds = image.world_bounds_mm();
    EXPECT_DOUBLE_EQ(bounds[0][0], -0.5);
    EXPECT_DOUBLE_EQ(bounds[1][0], 1.5);
    EXPECT_DOUBLE_EQ(bounds[0][2], -1.0);
    EXPECT_DOUBLE_EQ(bounds[1][2], 7.0);
}

TEST(LabelImage, RejectsBadGeometryWithMessage)
{
    EXPECT_THROW(LabelImage({0, 1, 1}, {1, 1, 1}), InputError);
    EXPECT_THROW(LabelImage({1, 1, 1}, {1, 0, 1}), InputError);
    EXPECT_THROW(LabelImage({1, 1, 1}, {1, NAN, 1}), InputError);
    EXPECT_THROW(LabelImage({1, 1, 1}, {-1, 1, 1}), InputError);
    EXPECT_THROW(LabelImage({1, 1, 1}, {1, 1, 1}, {}, {1, 0, 0, 1, 0, 0, 0, 0, 1}), InputError);
    try {
        validate_geometry("head.nii", {2, 2, 2}, {1, 1, 0}, identity_matrix());
        FAIL() << "zero spacing accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("head.nii: spacing along axis 2 is 0 mm"), std::string::npos) << e.what();
    }
}

TEST(LabelImage, CountsLabels)
{
    LabelImage image({3, 1, 1}, {1, 1, 1});
    image.at(1, 0, 0) = 7;
    image.at(2, 0, 0) = 65535;
    const auto counts = count_labels(image);
    ASSERT_EQ(counts.size(), 3u);
    EXPECT_EQ(counts.at(0), 1u);
    EXPECT_EQ(counts.at(65535), 1u);
    EXPECT_EQ(image.name_of(7), "7");
}

TEST(AtomicFile, FailedWriteLeavesNothing)
{
    testing::TempDir dir;
    EXPECT_THROW(write_atomically(dir / "out.txt",
                                  [](const std::filesystem::path& tmp) {
                                      write_text_atomically(tmp, "partial");
                                      throw AlgorithmError("stop");
                                  }),
                 AlgorithmError);
    EXPECT_TRUE(dir.files().empty());
    write_text_atomically(dir / "out.txt", "done");
    EXPECT_EQ(dir.files(), std::vector<std::string>{"out.txt"});
    EXPECT_THROW(write_text_atomically(dir / "missing" / "x.txt", "x"), IoError);
}

TEST(AtomicFile, FullExtensionKeepsCompression)
{
    EXPECT_EQ(full_extension("a/b.NII.gz"), ".nii.gz");
    EXPECT_EQ(full_extension("head.nii"), ".nii");
    EXPECT_EQ(full_extension("x.seg.nrrd"), ".seg.nrrd");
    EXPECT_EQ(full_extension("noext"), "");
}

} // namespace
} // namespace tissuemesh

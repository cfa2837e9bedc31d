// Write then read every format: geometry, labels and (where the format keeps them) names survive.
#include <gtest/gtest.h>

#include "core/error.h"
#include "io/read_label_image.h"
#include "io/write_label_image.h"
#include "tests/io/expect_error.h"
#include "tests/io/make_test_images.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

struct FormatCase {
    std::string extension;
    bool keeps_direction; ///< false: the format stores no orientation (Inrimage)
    bool keeps_names;
};

class RoundTrip : public ::testing::TestWithParam<FormatCase> {};

void expect_same_geometry(const LabelImage& expected, const LabelImage& actual, bool with_direction)
{
    EXPECT_EQ(actual.dims(), expected.dims());
    for (int a = 0; a < 3; ++a) {
        // Headers store spacing and origin as float32 in NIfTI-1: 1e-5 mm covers the rounding.
        EXPECT_NEAR(actual.spacing_mm()[a], expected.spacing_mm()[a], 1e-5) << "axis " << a;
        EXPECT_NEAR(actual.origin_mm()[a], expected.origin_mm()[a], 1e-5) << "axis " << a;
    }
    if (with_direction) {
        for (int n = 0; n < 9; ++n) EXPECT_NEAR(actual.direction()[n], expected.direction()[n], 1e-6) << n;
    }
}

TEST_P(RoundTrip, KeepsGeometryLabelsAndNames)
{
    const FormatCase& format = GetParam();
    testing::TempDir dir;
    LabelImage image = testing::make_oriented_image();
    if (!format.keeps_direction) image = LabelImage(image.dims(), image.spacing_mm(), image.origin_mm());
    image.labels() = testing::make_oriented_image().labels();
    image.names() = {{1, "scalp"}, {2, "skull"}, {25, "white matter"}};
    const auto path = dir / ("head" + format.extension);
    io::write_label_image(image, path);
    const LabelImage back = io::read_label_image(path);
    expect_same_geometry(image, back, format.keeps_direction);
    EXPECT_EQ(back.labels(), image.labels());
    if (format.keeps_names) {
        // Every tissue reads back under the name it was written with (its number when it had none).
        for (const auto& [label, count] : count_labels(image)) EXPECT_EQ(back.name_of(label), image.name_of(label));
        EXPECT_EQ(back.names().at(25), "white matter");
    }
    // World positions agree voxel by voxel: the orientation is RAS in and out.
    const Vec3 corner{4, 3, 2};
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(back.index_to_world(corner)[a], image.index_to_world(corner)[a], 1e-4);
    // Only the result is left behind (no temporary files).
    for (const std::string& file : dir.files()) EXPECT_FALSE(file.starts_with(".tmp")) << file;
}

TEST_P(RoundTrip, KeepsLabelsAbove255AsUint16)
{
    const FormatCase& format = GetParam();
    testing::TempDir dir;
    LabelImage image = testing::make_oriented_image(2600); // up to 25 * 2600 = 65000
    if (!format.keeps_direction) {
        const auto labels = image.labels();
        image = LabelImage(image.dims(), image.spacing_mm(), image.origin_mm());
        image.labels() = labels;
    }
    image.at(0, 0, 0) = 65535;
    const auto path = dir / ("big" + format.extension);
    io::write_label_image(image, path);
    const LabelImage back = io::read_label_image(path);
    EXPECT_EQ(back.labels(), image.labels());
    expect_same_geometry(image, back, format.keeps_direction);
}

INSTANTIATE_TEST_SUITE_P(Formats, RoundTrip,
                         ::testing::Values(FormatCase{".nii.gz", true, false}, FormatCase{".nii", true, false},
                                           FormatCase{".nrrd", true, false}, FormatCase{".seg.nrrd", true, true},
                                           FormatCase{".nhdr", true, false}, FormatCase{".mha", true, false},
                                           FormatCase{".mhd", true, false}, FormatCase{".inr", false, false},
                                           FormatCase{".inr.gz", false, false}, FormatCase{".json", true, true}),
                         [](const auto& test_info) {
                             std::string name = test_info.param.extension.substr(1);
                             for (char& c : name)
                                 if (c == '.') c = '_';
                             return name;
                         });

TEST(WriteLabelImage, RejectsUnknownExtensionAndLeavesNothing)
{
    testing::TempDir dir;
    try {
        io::write_label_image(testing::make_oriented_image(), dir / "head.xyz");
        FAIL() << "unknown extension accepted";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("head.xyz: unknown image format '.xyz'"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(dir.files().empty());
}

TEST(WriteLabelImage, RejectsMissingFoldersForEveryFormat)
{
    testing::TempDir dir;
    for (const std::string extension : {".nii.gz", ".nhdr", ".mhd", ".inr", ".json"})
        testing::expect_error<IoError>(
            [&] {
                io::write_label_image(LabelImage({2, 2, 2}, {1, 1, 1}), dir / "missing" / ("a" + extension));
            },
            {"does not exist; create it first"});
    EXPECT_TRUE(dir.files().empty());
}

TEST(WriteLabelImage, IsByteForByteDeterministic)
{
    testing::TempDir dir;
    const LabelImage image = testing::make_oriented_image();
    io::write_label_image(image, dir / "a.nii.gz");
    io::write_label_image(image, dir / "b.nii.gz");
    std::ifstream a(dir / "a.nii.gz", std::ios::binary), b(dir / "b.nii.gz", std::ios::binary);
    const std::string bytes_a((std::istreambuf_iterator<char>(a)), {}),
        bytes_b((std::istreambuf_iterator<char>(b)), {});
    EXPECT_EQ(bytes_a, bytes_b);
}

} // namespace
} // namespace tissuemesh

// FreeSurfer MGH volumes built byte by byte: the geometry nibabel gives them (world = centre + Mdc * spacing *
// (index - dims / 2)), its default when goodRASFlag is 0, and a clear error for every lying or unfit header.
// (Files written by nibabel itself, .mgz included: tests/io_clients/test_nibabel.cpp.)
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

#include "core/error.h"
#include "io/read_label_image.h"
#include "tests/io/expect_error.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

using testing::expect_error;

/// The fields of an MGH header, and the bytes of a file with them.
struct Mgh {
    std::int32_t version = 1, width = 3, height = 4, depth = 5, frames = 1, type = 0;
    std::int16_t good_ras = 1;
    float spacing[3] = {1.0f, 2.0f, 3.0f};
    float mdc[3][3] = {{0, 1, 0}, {-1, 0, 0}, {0, 0, 1}}; // row i: the world direction of voxel axis i
    float centre[3] = {10.0f, 20.0f, 30.0f};
    std::size_t voxel_bytes = 1;
    std::int64_t drop_bytes = 0; ///< cut this many bytes off the end (a lying header)

    std::string bytes() const
    {
        std::string out;
        auto put = [&](const void* value, std::size_t size) {
            const auto* raw = static_cast<const unsigned char*>(value);
            for (std::size_t b = size; b-- > 0;) out += static_cast<char>(raw[b]); // big endian
        };
        for (const std::int32_t v : {version, width, height, depth, frames, type, std::int32_t{0}}) put(&v, 4);
        put(&good_ras, 2);
        for (const float v : spacing) put(&v, 4);
        for (const auto& row : mdc)
            for (const float v : row) put(&v, 4);
        for (const float v : centre) put(&v, 4);
        out.resize(284, '\0');
        const std::size_t voxels = static_cast<std::size_t>(width) * height * depth * frames;
        for (std::size_t v = 0; v < voxels; ++v) {
            const auto label = static_cast<std::uint32_t>(v % 3);
            for (std::size_t b = voxel_bytes; b-- > 0;) out += static_cast<char>(b < 4 ? (label >> (8 * b)) & 0xff : 0);
        }
        out += std::string(20, '\0'); // the optional tags (TR, flip angle, ...) that follow the voxels
        out.resize(static_cast<std::size_t>(static_cast<std::int64_t>(out.size()) - drop_bytes));
        return out;
    }
};

class MghReader : public ::testing::Test {
protected:
    std::filesystem::path write(const std::string& name, const Mgh& mgh)
    {
        std::ofstream(dir_ / name, std::ios::binary) << mgh.bytes();
        return dir_ / name;
    }
    testing::TempDir dir_;
};

TEST_F(MghReader, VoxelIndexDimsOverTwoSitsAtTheCentre)
{
    const LabelImage image = io::read_label_image(write("a.mgh", Mgh{}));
    EXPECT_EQ(image.dims(), (Dims{3, 4, 5}));
    EXPECT_EQ(image.spacing_mm(), (Vec3{1, 2, 3}));
    // Axis i runs along Mdc row i: i along +y, j along -x, k along +z; index (1.5, 2, 2.5) is the centre.
    const Vec3 centre = image.index_to_world({1.5, 2, 2.5});
    for (std::size_t a = 0; a < 3; ++a) EXPECT_NEAR(centre[a], (Vec3{10, 20, 30})[a], 1e-12);
    const Vec3 corner = image.index_to_world({-0.5, -0.5, -0.5}); // the outer corner of voxel (0, 0, 0)
    const Vec3 expected{10 + 2 * 2.5, 20 - 1 * 2, 30 - 3 * 3};
    for (std::size_t a = 0; a < 3; ++a) EXPECT_NEAR(corner[a], expected[a], 1e-12) << a;
    EXPECT_EQ(image.at(1, 0, 0), 1);
    EXPECT_EQ(image.at(2, 3, 4), (2 + 3 * (3 + 4 * 4)) % 3);
}

TEST_F(MghReader, NibabelsDefaultWhenTheGeometryIsFlaggedInvalid)
{
    Mgh mgh;
    mgh.good_ras = 0; // spacing, Mdc and centre are then ignored, as nibabel does
    const LabelImage image = io::read_label_image(write("b.mgh", mgh));
    EXPECT_EQ(image.spacing_mm(), (Vec3{1, 1, 1}));
    EXPECT_EQ(image.direction(), (Mat3{-1, 0, 0, 0, 0, -1, 0, 1, 0})); // columns (-1,0,0), (0,0,1), (0,-1,0)
    const Vec3 centre = image.index_to_world({1.5, 2, 2.5});
    for (std::size_t a = 0; a < 3; ++a) EXPECT_NEAR(centre[a], 0.0, 1e-12);
}

TEST_F(MghReader, EveryVoxelTypeOfLabels)
{
    for (const auto& [type, bytes] : std::vector<std::pair<int, std::size_t>>{{0, 1}, {4, 2}, {1, 4}, {10, 2}}) {
        Mgh mgh;
        mgh.type = type;
        mgh.voxel_bytes = bytes;
        EXPECT_EQ(io::read_label_image(write("t.mgh", mgh)).at(2, 0, 0), 2) << "type " << type;
    }
}

TEST_F(MghReader, LyingOrUnfitHeadersAreRefusedWithTheFix)
{
    const auto refused = [&](const std::string& name, auto change, std::initializer_list<std::string> parts, bool io) {
        SCOPED_TRACE(name);
        Mgh mgh;
        change(mgh);
        const auto path = write(name, mgh);
        if (io) expect_error<IoError>([&] { io::read_label_image(path); }, parts);
        else expect_error<InputError>([&] { io::read_label_image(path); }, parts);
    };
    refused(
        "version.mgh", [](Mgh& m) { m.version = 2; }, {"version.mgh", "MGH version 2 is not 1"}, true);
    refused(
        "short.mgh", [](Mgh& m) { m.drop_bytes = 30; }, {"short.mgh", "truncated"}, true);
    refused(
        "header.mgh", [](Mgh& m) { m.drop_bytes = 200; }, {"header.mgh", "too few for an MGH header"}, true);
    refused(
        "frames.mgh", [](Mgh& m) { m.frames = 2; }, {"frames.mgh", "2 frames per voxel", "mri_convert --frame 0"},
        false);
    refused(
        "type.mgh", [](Mgh& m) { m.type = 6; }, {"type.mgh", "MGH voxel type 6 is not a label type"}, false);
    refused(
        "dims.mgh", [](Mgh& m) { m.height = 0; }, {"dims.mgh", "MGH dimension 1 is 0"}, false);
    refused(
        "spacing.mgh", [](Mgh& m) { m.spacing[2] = 0; }, {"spacing.mgh", "spacing along axis 2 is 0 mm"}, false);
    refused(
        "axes.mgh", [](Mgh& m) { m.mdc[1][0] = 0, m.mdc[1][1] = 1; }, {"axes.mgh", "orthonormal"}, false);
    refused(
        "zero.mgh", [](Mgh& m) { m.mdc[2][2] = 0; }, {"zero.mgh", "axis 2", "zero or not finite"}, false);
    refused(
        "float.mgh", [](Mgh& m) { m.type = 3, m.voxel_bytes = 4; }, {"float.mgh", "voxel"}, false);
}

} // namespace
} // namespace tissuemesh

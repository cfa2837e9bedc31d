// Valid files with bytes overwritten at deterministic pseudo-random places: the reader either reads
// an image that passes validate_geometry() or throws one of our errors, never anything else (no
// crash, no std::bad_alloc from a corrupt size, no ITK exception leaking through, nothing printed).
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/read_label_image.h"
#include "io/write_label_image.h"
#include "tests/io/make_test_images.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

std::string read_bytes(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

class CorruptedFiles : public ::testing::TestWithParam<std::string> {};

TEST_P(CorruptedFiles, ReadOrThrowOurErrors)
{
    testing::TempDir dir;
    const std::string extension = GetParam();
    LabelImage image({6, 5, 4}, {0.5, 1, 2});
    for (std::size_t n = 0; n < image.voxel_count(); ++n) image.labels()[n] = static_cast<Label>(n % 7);
    const auto original = dir / ("a" + extension);
    io::write_label_image(image, original);
    const std::string bytes = read_bytes(original);
    std::mt19937 random(12345); // fixed seed: the same corruptions on every run
    int read = 0, rejected = 0;
    ::testing::internal::CaptureStderr();
    for (int trial = 0; trial < 300; ++trial) {
        std::string corrupt = bytes;
        // Headers sit at the start: corrupt there more often than in the voxel data.
        const std::size_t span = trial % 2 == 0 ? std::min<std::size_t>(corrupt.size(), 400) : corrupt.size();
        for (int flips = 0; flips < 1 + trial % 4; ++flips)
            corrupt[random() % span] = static_cast<char>(random() % 256);
        if (trial % 10 == 9) corrupt.resize(random() % corrupt.size());
        const auto path = dir / ("c" + extension);
        std::ofstream(path, std::ios::binary) << corrupt;
        try {
            const LabelImage back = io::read_label_image(path);
            EXPECT_NO_THROW(validate_geometry("back", back.dims(), back.spacing_mm(), back.direction()));
            ++read;
        } catch (const Error&) {
            ++rejected;
        } catch (const std::exception& e) {
            ADD_FAILURE() << extension << " trial " << trial << ": " << typeid(e).name() << " " << e.what();
        }
    }
    // Library code never prints, whatever ITK and the nifti/NRRD/MetaIO libraries think of the bytes.
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
    EXPECT_GT(rejected, 0); // the corruptions do hit something
    RecordProperty("read", read);
}

INSTANTIATE_TEST_SUITE_P(Formats, CorruptedFiles,
                         ::testing::Values(".nii", ".nii.gz", ".nrrd", ".mha", ".inr", ".inr.gz"),
                         [](const auto& test_info) {
                             std::string name = test_info.param.substr(1);
                             for (char& c : name)
                                 if (c == '.') c = '_';
                             return name;
                         });

} // namespace
} // namespace tissuemesh

// Inputs the fuzzers (scripts/fuzz) found crashing a reader, kept in tests/fuzz/regressions/ under the bug's
// name: each must now give our typed error, naming the file and the defect.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "io/read_label_image.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

std::filesystem::path regression(const std::string& name)
{
    return std::filesystem::path(TM_DATA_DIR).parent_path() / "tests" / "fuzz" / "regressions" / name;
}

/// Reads regression file `name`, which must be refused with an `Expected` error whose message holds `part`.
template <typename Expected>
void expect_refused(const std::string& name, const std::string& part)
{
    try {
        (void)io::read_label_image(regression(name));
        FAIL() << "read " << name;
    } catch (const Expected& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find(part), std::string::npos) << message;
    }
}

// fuzz_nifti: sform_code 1 with a NaN in srow_z made ITK's vnl_svd abort the whole process.
TEST(FuzzRegressions, NiftiNanSform)
{
    expect_refused<InputError>("nifti-nan-sform.nii", "nifti-nan-sform.nii: the sform");
}

// fuzz_metaimage: a key without "=" ("ElementDataFile" alone on its line) made MetaIO take the next line as
// its value, a file pattern with "%n" and a zero step, and loop forever: tm-info hung on a 168-byte file.
TEST(FuzzRegressions, MetaimageKeyWithoutEqualsHangs)
{
    expect_refused<IoError>("metaimage-key-without-equals-hangs.mha",
                            "metaimage-key-without-equals-hangs.mha: header line 4 (\"ElementDataFile\")");
}

// fuzz_metaimage: "NDims = -1 - 0 0 1" made MetaIO read 2^32 numbers per field (its count is unsigned): a hang.
TEST(FuzzRegressions, MetaimageNegativeNdimsHangs)
{
    expect_refused<IoError>("metaimage-negative-ndims-hangs.mha",
                            "metaimage-negative-ndims-hangs.mha: NDims is '-1 - 0 0 1'");
}

// fuzz_metaimage: compressed voxel data whose zlib header asks for a preset dictionary made MetaIO's inflate
// loop spin forever (zlib answers Z_NEED_DICT, which MetaIO neither handles nor treats as an error). Three
// damaged header lines of the fuzzer's file were made plain by hand (such keys are refused first now).
TEST(FuzzRegressions, MetaimageZlibPresetDictionaryHangs)
{
    expect_refused<IoError>(
        "metaimage-zlib-preset-dictionary-hangs.mha",
        "metaimage-zlib-preset-dictionary-hangs.mha: its compressed voxel data is not one whole zlib stream");
}

// fuzz_metaimage: a header key of 345 bytes overran MetaIO's 255-byte field name (strcpy): an abort. The file
// is a valid 2x2x2 image with such a key added by hand (the fuzzer's input now fails an earlier check).
TEST(FuzzRegressions, MetaimageLongKeyOverflows)
{
    expect_refused<IoError>("metaimage-long-key-overflows.mha",
                            "metaimage-long-key-overflows.mha: header line 3 has a key of 345 characters");
}

// fuzz_metaimage: "NDims = 444...3" followed later by "NDims = 3": our check read the last one, MetaIO acted on
// the first and read billions of numbers per field (a hang). A MetaImage key may now come only once. The file
// is a valid 2x2x2 image with the two NDims lines, made by hand (the fuzzer's input fails an earlier check).
TEST(FuzzRegressions, MetaimageRepeatedNdimsHangs)
{
    expect_refused<IoError>("metaimage-repeated-ndims-hangs.mha",
                            "metaimage-repeated-ndims-hangs.mha: header line 3 repeats the key 'NDims'");
}

// fuzz_metaimage: "ElementDat aFile = LOCAL" (our check, which dropped spaces in keys, took it for the data file
// line) and later "ElementDataFile = Lppp%..." (MetaIO's data file, a pattern it overran a buffer on): ASan,
// heap-buffer-overflow in strlen. Keys with a space are now an error. A valid 2x2x2 image with both lines, by hand.
TEST(FuzzRegressions, MetaimageKeyWithSpaceOverflows)
{
    expect_refused<IoError>(
        "metaimage-key-with-space-overflows.mha",
        "metaimage-key-with-space-overflows.mha: header line 7 has a key with a space in it ('ElementDat aFile')");
}

} // namespace
} // namespace tissuemesh

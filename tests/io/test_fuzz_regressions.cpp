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

// fuzz_nifti: sform_code 1 with a NaN in srow_z made ITK's vnl_svd abort the whole process.
TEST(FuzzRegressions, NiftiNanSform)
{
    try {
        (void)io::read_label_image(regression("nifti-nan-sform.nii"));
        FAIL() << "read a header with a NaN sform";
    } catch (const InputError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("nifti-nan-sform.nii: the sform"), std::string::npos) << message;
    }
}

// fuzz_metaimage: a key without "=" ("ElementDataFile" alone on its line) made MetaIO take the next line as
// its value, a file pattern with "%n" and a zero step, and loop forever: tm-info hung on a 168-byte file.
TEST(FuzzRegressions, MetaimageKeyWithoutEqualsHangs)
{
    try {
        (void)io::read_label_image(regression("metaimage-key-without-equals-hangs.mha"));
        FAIL() << "read a header with a line that is not Key = Value";
    } catch (const IoError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("metaimage-key-without-equals-hangs.mha: header line 4 (\"ElementDataFile\")"),
                  std::string::npos) << message;
    }
}

// fuzz_metaimage: "NDims = -1 - 0 0 1" made MetaIO read 2^32 numbers per field (its count is unsigned): a hang.
TEST(FuzzRegressions, MetaimageNegativeNdimsHangs)
{
    try {
        (void)io::read_label_image(regression("metaimage-negative-ndims-hangs.mha"));
        FAIL() << "read a header with NDims -1";
    } catch (const IoError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("metaimage-negative-ndims-hangs.mha: NDims is '-1 - 0 0 1'"), std::string::npos) << message;
    }
}

} // namespace
} // namespace tissuemesh

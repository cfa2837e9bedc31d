// Broken and invalid NIfTI files: the reader names the file and the problem, and allocates nothing
// beyond what the file holds.
#include <algorithm>
#include <cmath>
#include <limits>
#include <gtest/gtest.h>

#include "core/error.h"
#include "io/read_label_image.h"
#include "tests/io/expect_read_error.h"
#include "tests/io/make_test_images.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

using testing::expect_read_error;

std::vector<unsigned char> eight_voxels() { return {0, 1, 2, 3, 4, 5, 6, 7}; }

TEST(BadInput, MissingFileDirectoryAndEmptyFile)
{
    testing::TempDir dir;
    expect_read_error<IoError>(dir / "none.nii.gz", {"none.nii.gz: no such file"});
    expect_read_error<IoError>(dir.path(), {"is a directory"});
    testing::write_bytes(dir / "empty.nii", {});
    expect_read_error<IoError>(dir / "empty.nii", {"empty.nii: the file is empty"});
}

TEST(BadInput, UnknownExtension)
{
    testing::TempDir dir;
    testing::write_bytes(dir / "head.png", {1, 2, 3});
    expect_read_error<IoError>(dir / "head.png", {"head.png: unknown image format '.png'", ".nii.gz"});
}

TEST(BadInput, ValidHandMadeNiftiReads)
{
    // The control for the broken files below: the same writer with sane fields reads fine.
    testing::TempDir dir;
    testing::NiftiSpec spec;
    spec.spacing[2] = 2.5f;
    testing::write_nifti(dir / "ok.nii", spec, eight_voxels());
    const LabelImage image = io::read_label_image(dir / "ok.nii");
    EXPECT_EQ(image.dims(), (Dims{2, 2, 2}));
    EXPECT_EQ(image.at(1, 1, 1), 7);
    EXPECT_FLOAT_EQ(static_cast<float>(image.spacing_mm()[2]), 2.5f);
}

TEST(BadInput, Nifti2ReadsAndIsChecked)
{
    testing::TempDir dir;
    testing::write_nifti2(dir / "two.nii", {2, 2, 2}, eight_voxels());
    const LabelImage image = io::read_label_image(dir / "two.nii");
    EXPECT_EQ(image.at(1, 1, 1), 7);
    EXPECT_EQ(image.spacing_mm(), (Vec3{1, 2, 3}));
    // The sform wins over the (identity) qform: axes permuted, i -> -y (2 mm), j -> +x (3 mm), k -> z (4 mm).
    testing::write_nifti2(dir / "rot.nii", {2, 2, 2}, eight_voxels(), {0, 3, 0, 10, -2, 0, 0, 20, 0, 0, 4, 30});
    const LabelImage rotated = io::read_label_image(dir / "rot.nii");
    EXPECT_EQ(rotated.spacing_mm(), (Vec3{2, 3, 4}));
    const Vec3 world = rotated.index_to_world({1, 1, 1});
    EXPECT_EQ(world, (Vec3{13, 18, 34}));
    testing::write_nifti2(dir / "short2.nii", {2, 2, 3}, eight_voxels());
    expect_read_error<IoError>(dir / "short2.nii", {"short2.nii: truncated", "need 12 bytes", "holds 8"});
}

TEST(BadInput, Nifti2QformMatchesItksNifti1Qform)
{
    // The same qform (a rotation by 2 * acos(a) about (1, 2, 3), third axis flipped, offset) read
    // by ITK from NIfTI-1 and by our own code from NIfTI-2 places every voxel at the same point.
    testing::TempDir dir;
    const double b = 0.1, c = 0.2, d = 0.3;
    testing::NiftiSpec spec;
    spec.spacing[0] = 1;
    spec.spacing[1] = 2;
    spec.spacing[2] = 3;
    const float quatern[6] = {0.1f, 0.2f, 0.3f, -5.5f, 7.25f, 12.0f};
    std::copy(quatern, quatern + 6, spec.quatern);
    spec.qfac = -1;
    testing::write_nifti(dir / "one.nii", spec, eight_voxels());
    testing::write_nifti2(dir / "two.nii", {2, 2, 2}, eight_voxels(), {},
                          {static_cast<float>(b), static_cast<float>(c), static_cast<float>(d), -5.5, 7.25, 12.0}, -1);
    const LabelImage one = io::read_label_image(dir / "one.nii");
    const LabelImage two = io::read_label_image(dir / "two.nii");
    for (const Vec3& index : {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 1}, Vec3{1, 1, 1}}) {
        const Vec3 p = one.index_to_world(index), q = two.index_to_world(index);
        // float32 quaternion in both files; ITK renormalizes the rotation: 1e-4 mm.
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(p[a], q[a], 1e-4) << index[0] << index[1] << index[2];
    }
    EXPECT_LT(determinant(two.direction()), 0); // qfac = -1: a left-handed grid
}

TEST(BadInput, NiftiScalingIsAppliedBeforeTheLabelChecks)
{
    // scl_slope/scl_inter turn stored values into the image's values: labels are 2 * stored + 1.
    testing::TempDir dir;
    testing::NiftiSpec spec{.scale_slope = 2, .scale_intercept = 1};
    testing::write_nifti(dir / "scaled.nii", spec, eight_voxels());
    EXPECT_EQ(io::read_label_image(dir / "scaled.nii").at(1, 1, 1), 15);
    spec.scale_slope = 0.5f;
    testing::write_nifti(dir / "halved.nii", spec, eight_voxels());
    expect_read_error<InputError>(dir / "halved.nii", {"halved.nii: voxel (1, 0, 0) holds 1.5"});
}

TEST(BadInput, TruncatedNifti)
{
    testing::TempDir dir;
    testing::write_nifti(dir / "short.nii", {}, {0, 1, 2});
    expect_read_error<IoError>(dir / "short.nii", {"short.nii: truncated", "need 8 bytes", "holds 3"});
    testing::write_bytes(dir / "header.nii", {0x5c, 0x01, 0, 0, 0, 0});
    expect_read_error<IoError>(dir / "header.nii", {"header.nii: truncated NIfTI header"});
}

TEST(BadInput, WrongMagic)
{
    testing::TempDir dir;
    testing::NiftiSpec spec;
    spec.magic[1] = 'x';
    testing::write_nifti(dir / "magic.nii", spec, eight_voxels());
    expect_read_error<IoError>(dir / "magic.nii", {"magic.nii: not a NIfTI file", "magic"});
    testing::write_bytes(dir / "text.nii.gz", std::vector<unsigned char>(400, 'a'));
    expect_read_error<IoError>(dir / "text.nii.gz", {"text.nii.gz: not a NIfTI file"});
}

TEST(BadInput, UnsupportedDatatype)
{
    // Datatype 1 (packed bits) is not a voxel type a label map uses; the nifti library would print.
    testing::TempDir dir;
    const testing::NiftiSpec spec{.datatype = 1, .bitpix = 1};
    testing::write_nifti(dir / "bits.nii", spec, eight_voxels());
    ::testing::internal::CaptureStderr();
    expect_read_error<IoError>(dir / "bits.nii", {"bits.nii: unsupported NIfTI datatype 1"});
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST(BadInput, BadSpacing)
{
    testing::TempDir dir;
    const std::vector<std::pair<float, std::string>> cases{
        {0.0f, "is 0 mm"}, {-1.5f, "is -1.5 mm"}, {std::nanf(""), "is nan mm"}, {INFINITY, "is inf mm"}};
    for (const auto& [value, text] : cases) {
        testing::NiftiSpec spec;
        spec.spacing[1] = value;
        testing::write_nifti(dir / "spacing.nii", spec, eight_voxels());
        expect_read_error<InputError>(dir / "spacing.nii",
                                      {"spacing.nii: spacing along axis 1 " + text, "positive finite"});
    }
}

TEST(BadInput, DimsExceedingTheFile)
{
    testing::TempDir dir;
    testing::NiftiSpec spec;
    spec.dims[1] = spec.dims[2] = spec.dims[3] = 30000; // 2.7e13 voxels from a 360-byte file
    testing::write_nifti(dir / "huge.nii", spec, eight_voxels());
    expect_read_error<IoError>(dir / "huge.nii", {"huge.nii: truncated", "27000000000000"});
    spec.dims[1] = -4;
    testing::write_nifti(dir / "negative.nii", spec, eight_voxels());
    expect_read_error<InputError>(dir / "negative.nii", {"negative.nii: dimension 0 is -4"});
}

TEST(BadInput, FloatLabelsMustBeWholeNumbers)
{
    testing::TempDir dir;
    const testing::NiftiSpec spec{.datatype = 16, .bitpix = 32};
    testing::write_nifti(dir / "whole.nii", spec, testing::voxel_bytes<float>({0, 1, 2, 3, 4, 5, 6, 300}));
    EXPECT_EQ(io::read_label_image(dir / "whole.nii").at(1, 1, 1), 300);
    testing::write_nifti(dir / "prob.nii", spec, testing::voxel_bytes<float>({0, 1, 2, 3, 4, 2.5f, 6, 7}));
    expect_read_error<InputError>(dir / "prob.nii", {"prob.nii: voxel (1, 0, 1) holds 2.5", "whole numbers"});
}

/// Regression: niftilib (under ITK) reads a NaN voxel of a NIfTI-1 float image as 0, so a broken label became
/// background without a word (tm-info counted it as tissue 0). Our own scan refuses it, in either byte order.
TEST(BadInput, NanLabelsAreRefusedNotReadAsBackground)
{
    testing::TempDir dir;
    for (const bool swapped : {false, true}) {
        const testing::NiftiSpec spec{.datatype = 16, .bitpix = 32, .swapped = swapped};
        std::vector<unsigned char> data = testing::voxel_bytes<float>({1, 1, 1, 1, 1, std::nanf(""), 2, 2});
        if (swapped)
            for (std::size_t v = 0; v < 8; ++v) std::reverse(data.begin() + 4 * v, data.begin() + 4 * v + 4);
        testing::write_nifti(dir / "nan.nii", spec, data);
        expect_read_error<InputError>(dir / "nan.nii", {"nan.nii: voxel (1, 0, 1)", "not a finite number"});
    }
    const testing::NiftiSpec doubles{.datatype = 64, .bitpix = 64};
    testing::write_nifti(dir / "inf.nii", doubles,
                         testing::voxel_bytes<double>({0, 1, 2, 3, 4, 5, 6, std::numeric_limits<double>::infinity()}));
    expect_read_error<InputError>(dir / "inf.nii", {"inf.nii: voxel (1, 1, 1)"});
}

TEST(BadInput, LabelsOutsideUint16)
{
    testing::TempDir dir;
    const testing::NiftiSpec spec{.datatype = 8, .bitpix = 32}; // int32
    testing::write_nifti(dir / "big.nii", spec, testing::voxel_bytes<std::int32_t>({0, 1, 2, 70000, 4, 5, 6, 7}));
    expect_read_error<InputError>(dir / "big.nii", {"big.nii: voxel (1, 1, 0) holds 70000", "0..65535"});
    testing::write_nifti(dir / "neg.nii", spec, testing::voxel_bytes<std::int32_t>({0, -3, 2, 3, 4, 5, 6, 7}));
    expect_read_error<InputError>(dir / "neg.nii", {"neg.nii: voxel (1, 0, 0) holds -3", "0..65535"});
}

TEST(BadInput, VectorImages)
{
    testing::TempDir dir;
    const testing::NiftiSpec spec{.vectors = 3};
    testing::write_nifti(dir / "vector.nii", spec, std::vector<unsigned char>(24, 1));
    expect_read_error<InputError>(dir / "vector.nii", {"vector.nii: a 5D image with 3 values", "one value per voxel"});
    const testing::NiftiSpec rgb{.datatype = 128, .bitpix = 24};
    testing::write_nifti(dir / "rgb.nii", rgb, std::vector<unsigned char>(24, 1));
    expect_read_error<InputError>(dir / "rgb.nii", {"rgb.nii: NIfTI datatype 128", "one value per voxel"});
}

} // namespace
} // namespace tissuemesh

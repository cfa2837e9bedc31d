// Broken and invalid NRRD, MetaImage, Inrimage and raw + JSON files, made in code.
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/read_label_image.h"
#include "io/write_label_image.h"
#include "tests/io/expect_error.h"
#include "tests/io/expect_read_error.h"
#include "tests/io/make_test_images.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

using testing::expect_error;
using testing::expect_read_error;
using testing::write_text;

std::string inr_header(const std::string& fields)
{
    std::string header = "#INRIMAGE-4#{\n" + fields;
    header.append(256 - header.size() - 4, '\n');
    return header + "##}\n";
}

const std::string inr_fields = "XDIM=2\nYDIM=2\nZDIM=2\nVDIM=1\nTYPE=unsigned fixed\nPIXSIZE=8 bits\nCPU=decm\n";

TEST(BadInrimage, ControlReads)
{
    testing::TempDir dir;
    write_text(dir / "ok.inr",
               inr_header(inr_fields + "VX=0.5\nVY=1\nVZ=2\nTX=1\nTY=2\nTZ=3\n") + std::string("\0\1\2\3\4\5\6\7", 8));
    const LabelImage image = io::read_label_image(dir / "ok.inr");
    EXPECT_EQ(image.at(1, 1, 1), 7);
    EXPECT_EQ(image.spacing_mm(), (Vec3{0.5, 1, 2}));
    EXPECT_EQ(image.origin_mm(), (Vec3{1, 2, 3}));
}

TEST(BadInrimage, TruncatedWrongMagicVectorAndSpacing)
{
    testing::TempDir dir;
    write_text(dir / "short.inr", inr_header(inr_fields) + "\1\2\3");
    expect_read_error<IoError>(dir / "short.inr", {"short.inr: truncated", "holds 3"});
    write_text(dir / "cut.inr", "#INRIMAGE-4#{\nXDIM=2\n");
    expect_read_error<IoError>(dir / "cut.inr", {"cut.inr: truncated Inrimage header"});
    write_text(dir / "magic.inr", std::string(300, 'x'));
    expect_read_error<IoError>(dir / "magic.inr", {"magic.inr: not an Inrimage", "magic"});
    write_text(dir / "vector.inr", inr_header("XDIM=2\nYDIM=2\nZDIM=2\nVDIM=3\n") + std::string(24, '\1'));
    expect_read_error<InputError>(dir / "vector.inr", {"vector.inr: 3 values per voxel"});
    write_text(dir / "zero.inr", inr_header(inr_fields + "VX=0\n") + std::string(8, '\1'));
    expect_read_error<InputError>(dir / "zero.inr", {"zero.inr: spacing along axis 0 is 0 mm"});
    write_text(dir / "nan.inr", inr_header(inr_fields + "VZ=nan\n") + std::string(8, '\1'));
    expect_read_error<InputError>(dir / "nan.inr", {"nan.inr: spacing along axis 2 is nan mm"});
    write_text(dir / "huge.inr", inr_header("XDIM=4000000000\nYDIM=4000000000\nZDIM=4000000000\n") + "\1");
    expect_read_error<InputError>(dir / "huge.inr", {"huge.inr: dimensions", "overflow"});
}

TEST(BadInrimage, WritingARotatedImageIsRefused)
{
    testing::TempDir dir;
    expect_error<InputError>([&] { io::write_label_image(testing::make_oriented_image(), dir / "rot.inr.gz"); },
                             {"rot.inr.gz: Inrimage cannot store the image's orientation", ".nii.gz"});
    EXPECT_TRUE(dir.files().empty());
}

const std::string raw_json = R"({"dims": [2, 2, 2], "spacing": [1, 1, 1], "dtype": "uint8", "raw_file": "v.raw")";

TEST(BadRawJson, ControlReadsBigEndianWithNames)
{
    testing::TempDir dir;
    write_text(dir / "v.raw", std::string("\0\1\0\2\0\3\0\4\1\0\0\0\0\0\0\7", 16));
    write_text(dir / "v.json", R"({"dims": [2, 2, 2], "spacing": [1, 2, 3], "dtype": "uint16", "byte_order": "big",
        "raw_file": "v.raw", "labels": {"256": "implant"}})");
    const LabelImage image = io::read_label_image(dir / "v.json");
    EXPECT_EQ(image.at(0, 0, 0), 1);
    EXPECT_EQ(image.at(0, 0, 1), 256);
    EXPECT_EQ(image.name_of(256), "implant");
}

TEST(BadRawJson, TruncatedMissingAndInvalidKeys)
{
    testing::TempDir dir;
    write_text(dir / "v.raw", "\1\2\3");
    write_text(dir / "short.json", raw_json + "}");
    expect_read_error<IoError>(dir / "short.json", {"v.raw: truncated", "holds 3"});
    write_text(dir / "missing.json",
               R"({"dims": [2, 2, 2], "spacing": [1, 1, 1], "dtype": "uint8", "raw_file": "no.raw"})");
    expect_read_error<IoError>(dir / "missing.json", {"missing.json: its raw file", "no.raw"});
    write_text(dir / "syntax.json", "{\"dims\": [2, 2");
    expect_read_error<IoError>(dir / "syntax.json", {"syntax.json: not a valid JSON"});
    write_text(dir / "nodims.json", R"({"spacing": [1, 1, 1]})");
    expect_read_error<InputError>(dir / "nodims.json", {"nodims.json: the key \"dims\""});
    write_text(dir / "dtype.json",
               R"({"dims": [2, 2, 2], "spacing": [1, 1, 1], "dtype": "complex64", "raw_file": "v.raw"})");
    expect_read_error<InputError>(dir / "dtype.json", {"dtype.json: unknown dtype \"complex64\""});
    write_text(dir / "neg.json",
               R"({"dims": [2, 2, 2], "spacing": [1, -2, 1], "dtype": "uint8", "raw_file": "v.raw"})");
    expect_read_error<InputError>(dir / "neg.json", {"neg.json: spacing along axis 1 is -2 mm"});
    write_text(dir / "null.json",
               R"({"dims": [2, 2, 2], "spacing": [1, null, 1], "dtype": "uint8", "raw_file": "v.raw"})");
    expect_read_error<InputError>(dir / "null.json", {"null.json: \"spacing\" must be an array of 3 numbers"});
    write_text(
        dir / "huge.json",
        R"({"dims": [4000000000, 4000000000, 4000000000], "spacing": [1, 1, 1], "dtype": "uint8", "raw_file": "v.raw"})");
    expect_read_error<InputError>(dir / "huge.json", {"huge.json: dimensions", "overflow"});
    write_text(dir / "big.json",
               R"({"dims": [200, 200, 200], "spacing": [1, 1, 1], "dtype": "float64", "raw_file": "v.raw"})");
    expect_read_error<IoError>(dir / "big.json", {"v.raw: truncated", "64000000 bytes"});
}

TEST(BadRawJson, FloatAndSignedValues)
{
    testing::TempDir dir;
    testing::write_bytes(dir / "f.raw", testing::voxel_bytes<double>({0, 1, 2, 3, 4, 5, 6, 0.25}));
    write_text(dir / "f.json", R"({"dims": [2, 2, 2], "spacing": [1, 1, 1], "dtype": "float64", "raw_file": "f.raw"})");
    expect_read_error<InputError>(dir / "f.json", {"f.raw: voxel (1, 1, 1) holds 0.25"});
    testing::write_bytes(dir / "s.raw", testing::voxel_bytes<std::int16_t>({0, 1, 2, 3, -1, 5, 6, 7}));
    write_text(dir / "s.json", R"({"dims": [2, 2, 2], "spacing": [1, 1, 1], "dtype": "int16", "raw_file": "s.raw"})");
    expect_read_error<InputError>(dir / "s.json", {"s.raw: voxel (0, 0, 1) holds -1"});
}

const std::string nrrd_head = "NRRD0004\ntype: uint8\ndimension: 3\nspace: left-posterior-superior\nsizes: 2 2 2\n"
                              "endian: little\nencoding: raw\n";

TEST(BadNrrd, ControlReads)
{
    testing::TempDir dir;
    write_text(dir / "ok.nrrd", nrrd_head + "space directions: (1,0,0) (0,2,0) (0,0,3)\nspace origin: (1,2,3)\n\n" +
                                    std::string("\0\1\2\3\4\5\6\7", 8));
    const LabelImage image = io::read_label_image(dir / "ok.nrrd");
    EXPECT_EQ(image.at(1, 1, 1), 7);
    EXPECT_EQ(image.spacing_mm(), (Vec3{1, 2, 3}));
    // LPS (1, 2, 3) is RAS (-1, -2, 3).
    EXPECT_EQ(image.origin_mm(), (Vec3{-1, -2, 3}));
}

TEST(BadNrrd, TruncatedZeroSpacingVectorsAndLayers)
{
    testing::TempDir dir;
    const std::string geometry = "space directions: (1,0,0) (0,1,0) (0,0,1)\n\n";
    write_text(dir / "short.nrrd", nrrd_head + geometry + "\1\2\3");
    expect_read_error<IoError>(dir / "short.nrrd", {"short.nrrd: truncated", "need 8 bytes"});
    write_text(dir / "magic.nrrd", "PNG\n" + geometry);
    expect_read_error<IoError>(dir / "magic.nrrd", {"magic.nrrd: not a NRRD file", "magic"});
    write_text(dir / "zero.nrrd", nrrd_head + "space directions: (1,0,0) (0,0,0) (0,0,1)\n\n" + std::string(8, '\1'));
    expect_read_error<InputError>(dir / "zero.nrrd", {"zero.nrrd: spacing along axis 1 is 0 mm"});
    write_text(dir / "vector.nrrd",
               "NRRD0004\ntype: uint8\ndimension: 4\nspace: left-posterior-superior\n"
               "sizes: 3 2 2 2\nkinds: vector domain domain domain\nendian: little\nencoding: raw\n"
               "space directions: none (1,0,0) (0,1,0) (0,0,1)\n\n" +
                   std::string(24, '\1'));
    expect_read_error<InputError>(dir / "vector.nrrd", {"vector.nrrd: 3 values per voxel"});
    write_text(dir / "layers.seg.nrrd",
               "NRRD0004\ntype: uint8\ndimension: 4\nspace: left-posterior-superior\n"
               "sizes: 2 2 2 2\nkinds: list domain domain domain\nendian: little\nencoding: raw\n"
               "space directions: none (1,0,0) (0,1,0) (0,0,1)\nSegment0_Name:=a\nSegment0_Layer:=0\n"
               "Segment1_Name:=b\nSegment1_Layer:=1\n\n" +
                   std::string(16, '\1'));
    expect_read_error<InputError>(dir / "layers.seg.nrrd",
                                  {"layers.seg.nrrd: a segmentation with 2 layers", "single-layer"});
}

TEST(BadNrrd, TruncatedCompressedDataIsAnIoErrorAndSilent)
{
    testing::TempDir dir;
    LabelImage image({40, 40, 40}, {1, 1, 1});
    for (std::size_t n = 0; n < image.voxel_count(); ++n) image.labels()[n] = static_cast<Label>(n * 7919 % 251);
    for (const std::string file : {"cut.nrrd", "cut.mha", "cut.nii.gz", "cut.inr.gz"}) {
        io::write_label_image(image, dir / file);
        const auto size = std::filesystem::file_size(dir / file);
        std::filesystem::resize_file(dir / file, size / 2);
        ::testing::internal::CaptureStderr();
        try {
            io::read_label_image(dir / file);
            ADD_FAILURE() << file << ": half a file accepted";
        } catch (const IoError& e) {
            EXPECT_NE(std::string(e.what()).find(file + ": "), std::string::npos) << e.what();
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        }
        // Library code never prints, even when ITK, MetaIO or zlib complain.
        EXPECT_EQ(::testing::internal::GetCapturedStderr(), "") << file;
    }
}

TEST(BadMetaImage, TruncatedAndWrongMagic)
{
    testing::TempDir dir;
    const std::string header = "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementSpacing = 1 1 1\n"
                               "ElementType = MET_UCHAR\nElementDataFile = LOCAL\n";
    write_text(dir / "short.mha", header + "\1\2\3");
    expect_read_error<IoError>(dir / "short.mha", {"short.mha: truncated", "holds 3"});
    write_text(dir / "magic.mha", "hello world\n");
    expect_read_error<IoError>(dir / "magic.mha", {"magic.mha: not a MetaImage file"});
    write_text(dir / "detached.mhd", "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\n"
                                     "ElementDataFile = gone.raw\n");
    expect_read_error<IoError>(dir / "detached.mhd", {"detached.mhd: its data file", "gone.raw"});
}

} // namespace
} // namespace tissuemesh

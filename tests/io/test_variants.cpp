// Files as other programs write them: big-endian NIfTI, RAS-space NRRD, Slicer segmentations written
// by Slicer rather than by us, and tissue-name tables.
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/read_label_image.h"
#include "tests/io/expect_error.h"
#include "tests/io/expect_read_error.h"
#include "tests/io/make_test_images.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

using testing::expect_error;
using testing::expect_read_error;
using testing::write_text;

TEST(Variants, BigEndianNifti)
{
    testing::TempDir dir;
    testing::NiftiSpec spec;
    spec.swapped = true;
    spec.datatype = 512; // uint16, stored big endian: 0x0102 = 258 at the last voxel
    spec.bitpix = 16;
    spec.spacing[2] = 2.5f;
    testing::write_nifti(dir / "big.nii", spec, {0, 0, 0, 1, 0, 2, 0, 3, 0, 4, 0, 5, 0, 6, 1, 2});
    const LabelImage image = io::read_label_image(dir / "big.nii");
    EXPECT_EQ(image.at(1, 0, 0), 1);
    EXPECT_EQ(image.at(1, 1, 1), 258);
    EXPECT_FLOAT_EQ(static_cast<float>(image.spacing_mm()[2]), 2.5f);
    spec.spacing[2] = 0;
    testing::write_nifti(dir / "bigzero.nii", spec, std::vector<unsigned char>(16, 0));
    expect_read_error<InputError>(dir / "bigzero.nii", {"bigzero.nii: spacing along axis 2 is 0 mm"});
}

TEST(Variants, NrrdInRasSpace)
{
    testing::TempDir dir;
    write_text(dir / "ras.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nspace: right-anterior-superior\nsizes: 2 2 2\n"
                                 "space directions: (0,2,0) (-1,0,0) (0,0,3)\nendian: little\nencoding: raw\n"
                                 "space origin: (10,20,30)\n\n" +
                                     std::string("\0\1\2\3\4\5\6\7", 8));
    const LabelImage image = io::read_label_image(dir / "ras.nrrd");
    // Our world is RAS: the header's RAS numbers come back unchanged.
    EXPECT_EQ(image.origin_mm(), (Vec3{10, 20, 30}));
    EXPECT_EQ(image.spacing_mm(), (Vec3{2, 1, 3}));
    const Vec3 world = image.index_to_world({1, 1, 1});
    EXPECT_EQ(world, (Vec3{9, 22, 33}));
}

TEST(Variants, SlicerSegmentationNames)
{
    testing::TempDir dir;
    const std::string head = "NRRD0004\ntype: uint8\ndimension: 3\nspace: left-posterior-superior\nsizes: 2 2 2\n"
                             "space directions: (1,0,0) (0,1,0) (0,0,1)\nendian: little\nencoding: raw\n";
    // Label values given explicitly, segments listed out of order.
    write_text(dir / "seg.seg.nrrd",
               head +
                   "Segment0_ID:=Segment_7\nSegment0_Name:=skull\nSegment0_LabelValue:=7\nSegment0_Layer:=0\n"
                   "Segment1_ID:=Segment_3\nSegment1_Name:=scalp\nSegment1_LabelValue:=3\nSegment1_Layer:=0\n\n" +
                   std::string("\0\3\3\7\0\0\7\7", 8));
    const LabelImage image = io::read_label_image(dir / "seg.seg.nrrd");
    EXPECT_EQ(image.names(), (TissueNames{{3, "scalp"}, {7, "skull"}}));
    // Without LabelValue (older files) segment N holds label N + 1.
    write_text(dir / "old.seg.nrrd",
               head + "Segment0_Name:=scalp\nSegment1_Name:=skull\n\n" + std::string("\0\1\1\2\0\0\2\2", 8));
    EXPECT_EQ(io::read_label_image(dir / "old.seg.nrrd").names(), (TissueNames{{1, "scalp"}, {2, "skull"}}));
    write_text(dir / "bad.seg.nrrd", head + "Segment0_Name:=scalp\nSegment0_LabelValue:=-4\n\n" + std::string(8, '\0'));
    expect_read_error<InputError>(dir / "bad.seg.nrrd", {"bad.seg.nrrd: segment 0 (scalp) has label value '-4'"});
}

TEST(Variants, NamesJsonOverridesTheFilesNames)
{
    testing::TempDir dir;
    LabelImage image({2, 1, 1}, {1, 1, 1});
    image.labels() = {1, 2};
    write_text(dir / "v.raw", std::string("\1\2", 2));
    write_text(dir / "v.json", R"({"dims": [2, 1, 1], "spacing": [1, 1, 1], "dtype": "uint8", "raw_file": "v.raw",
                                  "labels": {"1": "scalp", "2": "skull"}})");
    write_text(dir / "names.json", R"({"labels": {"2": "bone"}})");
    const LabelImage read = io::read_label_image(dir / "v.json", {.names_json = dir / "names.json"});
    EXPECT_EQ(read.names(), (TissueNames{{1, "scalp"}, {2, "bone"}}));
}

TEST(Variants, BadNameTables)
{
    testing::TempDir dir;
    write_text(dir / "key.json", R"({"scalp": "1"})");
    expect_error<InputError>([&] { io::read_tissue_names(dir / "key.json"); },
                             {"key.json: tissue-name key 'scalp' is not a label number in 0..65535"});
    write_text(dir / "range.json", R"({"70000": "implant"})");
    expect_error<InputError>([&] { io::read_tissue_names(dir / "range.json"); },
                             {"range.json: tissue-name key '70000'"});
    write_text(dir / "value.json", R"({"1": 5})");
    expect_error<InputError>([&] { io::read_tissue_names(dir / "value.json"); }, {"value.json: the name of label 1"});
    write_text(dir / "array.json", R"(["scalp"])");
    expect_error<InputError>([&] { io::read_tissue_names(dir / "array.json"); }, {"array.json: tissue names must be"});
    write_text(dir / "syntax.json", R"({"1": )");
    expect_error<IoError>([&] { io::read_tissue_names(dir / "syntax.json"); }, {"syntax.json: not valid JSON"});
    expect_error<IoError>([&] { io::read_tissue_names(dir / "none.json"); }, {"none.json: no such file"});
}

} // namespace
} // namespace tissuemesh

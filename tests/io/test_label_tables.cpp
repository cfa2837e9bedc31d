// Tissue names from the tables other tools write (FreeSurfer colour tables, ITK-SNAP label files, BIDS dseg.tsv),
// each found by --labels whatever its format, and SimNIBS tag tables; every defect refused with the file, the line
// and the layout expected.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "core/error.h"
#include "io/read_label_image.h"
#include "io/simnibs_tags.h"
#include "tests/io/expect_error.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

using testing::expect_error;

class LabelTables : public ::testing::Test {
protected:
    std::filesystem::path write(const std::string& name, const std::string& text)
    {
        std::ofstream(dir_ / name, std::ios::binary) << text;
        return dir_ / name;
    }
    testing::TempDir dir_;
};

TEST_F(LabelTables, FreeSurferColourTable)
{
    // As FreeSurferColorLUT.txt: a header comment, aligned columns, label 0, gaps in the numbering.
    const auto path =
        write("FreeSurferColorLUT.txt", "#$Id: FreeSurferColorLUT.txt $\n\n"
                                        "#No. Label Name:                            R   G   B   A\n"
                                        "0   Unknown                                 0   0   0   0\n"
                                        "2   Left-Cerebral-White-Matter            245 245 245   0\n"
                                        "3   Left-Cerebral-Cortex                  205  62  78   0\r\n"
                                        "24  CSF                                    60  60  60   0  # ventricles too\n"
                                        "1000    ctx-lh-unknown                     25   5  25   0\n");
    EXPECT_EQ(io::read_tissue_names(path), (TissueNames{{0, "Unknown"},
                                                        {2, "Left-Cerebral-White-Matter"},
                                                        {3, "Left-Cerebral-Cortex"},
                                                        {24, "CSF"},
                                                        {1000, "ctx-lh-unknown"}}));
}

TEST_F(LabelTables, ItkSnapLabelFile)
{
    const auto path = write("labels.txt", "################################################\n"
                                          "# ITK-SnAP Label Description File\n"
                                          "#    IDX   -R-  -G-  -B-  -A--  VIS MSH  LABEL\n"
                                          "    0     0    0    0        0  0  0    \"Clear Label\"\n"
                                          "    1   255    0    0        1  1  1    \"grey matter\"\n"
                                          "    2     0  255    0        1  1  1    \"white matter\"\n");
    EXPECT_EQ(io::read_tissue_names(path), (TissueNames{{0, "Clear Label"}, {1, "grey matter"}, {2, "white matter"}}));
}

TEST_F(LabelTables, BidsDsegTsv)
{
    const auto path = write("sub-01_dseg.tsv", "index\tname\tabbreviation\tcolor\n1\tGray Matter\tGM\t#ff53bb\n"
                                               "2\tWhite Matter\tWM\t#2f8bbe\n3\tCerebrospinal Fluid\tCSF\t#d8d8d8\n");
    EXPECT_EQ(io::read_tissue_names(path),
              (TissueNames{{1, "Gray Matter"}, {2, "White Matter"}, {3, "Cerebrospinal Fluid"}}));
    // Columns in any order.
    const auto swapped = write("b_dseg.tsv", "name\tindex\nscalp\t5\n");
    EXPECT_EQ(io::read_tissue_names(swapped), (TissueNames{{5, "scalp"}}));
}

TEST_F(LabelTables, JsonStillReadsWhateverTheExtension)
{
    EXPECT_EQ(io::read_tissue_names(write("names.txt", " {\"1\": \"scalp\"}")), (TissueNames{{1, "scalp"}}));
    EXPECT_EQ(io::read_tissue_names(write("names.json", "{\"labels\": {\"2\": \"skull\"}}")),
              (TissueNames{{2, "skull"}}));
}

TEST_F(LabelTables, DefectsNameTheFileTheLineAndTheLayout)
{
    expect_error<InputError>([&] { io::read_tissue_names(write("a.lut", "1 scalp 1 2 3 4\n2 grey matter 5 6 7 8\n")); },
                             {"a.lut line 2", "FreeSurfer colour table"});
    expect_error<InputError>([&] { io::read_tissue_names(write("b.lut", "1 scalp 1 2 3 4\n1 skin 1 2 3 4\n")); },
                             {"b.lut line 2", "label 1 is named twice", "scalp", "skin"});
    expect_error<InputError>([&] { io::read_tissue_names(write("c.lut", "70000 scalp 1 2 3 4\n")); },
                             {"c.lut line 1", "\"70000\" is not a label number in 0..65535"});
    expect_error<InputError>([&] { io::read_tissue_names(write("d.txt", "1 255 0 0 1 1 \"scalp\"\n")); },
                             {"d.txt line 1", "6 numbers before the name instead of 7", "ITK-SNAP"});
    expect_error<InputError>([&] { io::read_tissue_names(write("e.txt", "1 255 0 0 1 1 1 \"\"\n")); },
                             {"e.txt line 1", "label 1 has an empty name"});
    expect_error<InputError>([&] { io::read_tissue_names(write("f.tsv", "label\tname\n1\tscalp\n")); },
                             {"f.tsv line 1", "lacks \"index\"", "BIDS"});
    expect_error<InputError>([&] { io::read_tissue_names(write("g.tsv", "index\tname\n1\tscalp\textra\n")); },
                             {"g.tsv line 2", "3 tab-separated fields under a header of 2"});
    expect_error<InputError>([&] { io::read_tissue_names(write("h.lut", "# nothing but comments\n\n")); },
                             {"h.lut: the table names no label"});
}

TEST_F(LabelTables, SimnibsTagTables)
{
    EXPECT_EQ(io::read_simnibs_tag_table(write("t.json", "{\"air cavities\": 13, \"6\": 14}")),
              (io::SimnibsTagTable{{"air cavities", 13}, {"6", 14}}));
    expect_error<InputError>([&] { io::read_simnibs_tag_table(write("u.json", "{\"air\": 1000}")); },
                             {"u.json", "\"air\"", "1000", "1..999"});
    expect_error<InputError>(
        [&] { io::read_simnibs_tag_table(write("v.json", "{\"Air_Cavities\": 13, \"air cavities\": 14}")); },
        {"v.json", "given twice"});
    expect_error<IoError>([&] { io::read_simnibs_tag_table(write("w.json", "[13]")); },
                          {"w.json", "not a JSON object"});
}

TEST(SimnibsTags, NamesInAnyCaseOrSpellingAndNeverASilentDefault)
{
    TetMesh mesh;
    mesh.tet_labels = {1, 2, 3, 4, 5, 6};
    mesh.names = {{1, "Scalp"}, {2, "skull"}, {3, "CSF"}, {4, "Gray_Matter"}, {5, "white-matter"}, {6, "air cavities"}};
    expect_error<InputError>([&] { (void)io::simnibs_tags(mesh); },
                             {"no SimNIBS tag for \"air cavities\" (label 6)", "--tissue-tags", "scalp 5"});
    const std::map<Label, int> tags = io::simnibs_tags(mesh, {{"Air Cavities", 13}});
    EXPECT_EQ(tags, (std::map<Label, int>{{1, 5}, {2, 4}, {3, 3}, {4, 2}, {5, 1}, {6, 13}}));
    EXPECT_EQ(io::simnibs_tags(mesh, {{"6", 3}, {"3", 3}}).at(6), 3) << "a label key, and a merge the table asks for";
    expect_error<InputError>(
        [&] {
            (void)io::simnibs_tags(mesh, {{"6", 13}, {"bone marrow", 8}});
        },
        {"\"bone marrow\" names no tissue of the mesh", "\"air cavities\" (6)"});
    mesh.names[6] = "skin";
    expect_error<InputError>([&] { (void)io::simnibs_tags(mesh); },
                             {"\"Scalp\" and \"skin\" would both get SimNIBS tag 5"});
}

TEST(SimnibsTags, FaceTagsFollowItsMeshersHierarchy)
{
    EXPECT_EQ(io::simnibs_face_tag(1, 2), 1001); // white matter's surface
    EXPECT_EQ(io::simnibs_face_tag(3, 2), 1002); // grey matter's, against CSF
    EXPECT_EQ(io::simnibs_face_tag(3, 4), 1003);
    EXPECT_EQ(io::simnibs_face_tag(5, 4), 1004);   // bone ranks before scalp
    EXPECT_EQ(io::simnibs_face_tag(9, 3), 1009);   // blood before CSF
    EXPECT_EQ(io::simnibs_face_tag(13, 5), 1005);  // listed tags before the others
    EXPECT_EQ(io::simnibs_face_tag(14, 13), 1013); // the others in ascending order
}

} // namespace
} // namespace tissuemesh

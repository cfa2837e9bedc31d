// tools/tissue_arguments.h: the one parser of the tools' tissue arguments (issue 32).
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "tests/support/error_message.h"
#include "tools/extract_priority.h"
#include "tools/tissue_arguments.h"

namespace tissuemesh::tools {
namespace {

using testing::input_error_message;

/// The names of the usc19-5 head's label file ("CSF" in capitals), tissues 0..6 in the input.
TissueTable head_table()
{
    return {{{0, "ambient air"},
             {1, "scalp"},
             {2, "skull"},
             {3, "CSF"},
             {4, "grey matter"},
             {5, "white matter"},
             {6, "air cavities"}},
            {0, 1, 2, 3, 4, 5, 6},
            "head.nii.gz"};
}

TEST(TissueArguments, NamesAndNumbersGiveTheirLabels)
{
    const TissueTable table = head_table();
    EXPECT_EQ(parse_tissue("skull", table, "--tissue"), 2);
    EXPECT_EQ(parse_tissue("grey matter", table, "--tissue"), 4);
    EXPECT_EQ(parse_tissue("5", table, "--tissue"), 5);
    EXPECT_EQ(parse_tissue_list("scalp,3,white matter", table, "--tissues"), (std::vector<Label>{1, 3, 5}));
    const TissueSetting setting = parse_tissue_setting("csf=2.5", table, "--priority", "csf=1");
    EXPECT_EQ(setting.tissue, 3);
    EXPECT_EQ(setting.value, "2.5");
}

// Issue 32: tm-extract --priority csf=1 with a label file saying "CSF" failed, and its message listed no names.
TEST(TissueArguments, CsfMatchesALabelFileSayingCsfInCapitalsAndAnUnknownNameListsTheKnownOnes)
{
    const TissueTable table = head_table();
    EXPECT_EQ(parse_tissue("csf", table, "--priority"), 3);
    EXPECT_EQ(parse_tissue("Grey Matter", table, "--priority"), 4);
    const std::string message =
        input_error_message([&] { parse_tissue_setting("bone=1", table, "--priority", "csf=2,3=1"); });
    EXPECT_NE(message.find("--priority bone=1: unknown tissue \"bone\""), std::string::npos) << message;
    EXPECT_NE(message.find("head.nii.gz"), std::string::npos) << message;
    for (const char* known : {"1 scalp", "2 skull", "3 CSF", "4 grey matter", "6 air cavities"})
        EXPECT_NE(message.find(known), std::string::npos) << known << " not offered: " << message;
}

// Issue 32: tm-tetra --max-volume 65537=2 exited 0 and bounded tissue 1 (65537 wrapped to a 16-bit label).
TEST(TissueArguments, Label65537IsOutOfRangeNotTissue1)
{
    const TissueTable anything; // no names, labels present unknown: any label number is taken
    EXPECT_EQ(parse_tissue("65535", anything, "--max-volume"), 65535);
    for (const char* text : {"65537", "99999999999999999999999", "-1"}) {
        const std::string message = input_error_message([&] { parse_tissue(text, anything, "--max-volume 65537=2"); });
        EXPECT_NE(message.find(concat("tissue ", text, " is not a label number")), std::string::npos) << message;
        EXPECT_NE(message.find("0..65535"), std::string::npos) << message;
    }
}

TEST(TissueArguments, ALabelTheInputLacksIsAnErrorListingTheLabelsItHas)
{
    const std::string message = input_error_message([&] { parse_tissue("9", head_table(), "--tissues"); });
    EXPECT_NE(message.find("--tissues: head.nii.gz has no tissue 9; its tissues are 0 ambient air, 1 scalp"),
              std::string::npos)
        << message;
}

TEST(TissueArguments, ANameInTwoCasesForTwoLabelsAsksForTheNumber)
{
    const TissueTable table{{{3, "CSF"}, {7, "csf"}, {8, "Csf"}}, {3, 7, 8}, ""};
    EXPECT_EQ(parse_tissue("csf", table, "--priority"), 7) << "the exact name wins";
    const std::string message = input_error_message([&] { parse_tissue("cSF", table, "--priority"); });
    EXPECT_NE(message.find("give the label number"), std::string::npos) << message;
}

TEST(TissueArguments, ASettingWithoutValueShowsTheExample)
{
    const std::string message =
        input_error_message([] { parse_tissue_setting("csf", head_table(), "--priority", "csf=2,3=1"); });
    EXPECT_NE(message.find("--priority csf: expected TISSUE=VALUE"), std::string::npos) << message;
    EXPECT_NE(message.find("--priority csf=2,3=1"), std::string::npos) << message;
}

// Issue 32: tm-extract --priority and tm-assess --extract-priority are parsed by one function, "auto" included.
TEST(TissueArguments, ExtractPriorityIsPairsOrAutoAlone)
{
    LabelImage image({5, 1, 1}, {1, 1, 1});
    for (std::size_t i = 0; i < 5; ++i) image.at(i, 0, 0) = i < 4 ? 4 : 3; // 4 voxels of grey matter, 1 of CSF
    const TissueTable table = head_table();
    EXPECT_TRUE(parse_extract_priority({}, image, 0, table, "--priority").empty());
    EXPECT_EQ(parse_extract_priority({"csf=2", "4=-1"}, image, 0, table, "--priority"),
              (std::map<Label, int>{{3, 2}, {4, -1}}));
    const std::map<Label, int> ranked = parse_extract_priority({"auto"}, image, 0, table, "--priority");
    ASSERT_EQ(ranked.size(), 2u);
    EXPECT_GT(ranked.at(3), ranked.at(4)) << "the thinner tissue ranks higher";
    EXPECT_NE(input_error_message([&] {
                  parse_extract_priority({"auto", "csf=1"}, image, 0, table, "--extract-priority");
              }).find("--extract-priority auto ranks every tissue itself: give it alone"),
              std::string::npos);
    const std::string message =
        input_error_message([&] { parse_extract_priority({"csf=2.5"}, image, 0, table, "--priority"); });
    EXPECT_EQ(message, "--priority csf=2.5: expected TISSUE=INTEGER (e.g. --priority csf=2,3=1)");
}

} // namespace
} // namespace tissuemesh::tools

// tm-solve's small input files as library readers: sensors and electrode montages (CSV) and conductivity
// tables (JSON). Each accepted shape reads to the exact values; each defect gives our typed error with the
// file, the line where there is one, and the fix.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "io/read_conductivity_table.h"
#include "io/read_electrodes.h"
#include "io/read_sensors.h"
#include "tests/io/expect_error.h"
#include "tests/io/reader_files.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

using testing::expect_error;

class TableReaders : public testing::ReaderFiles {};

TEST_F(TableReaders, SensorsInAnyColumnOrderWithNamesCommentsAndWindowsLineEnds)
{
    const std::string file =
        write("cap.csv", "\xEF\xBB\xBF# 3 of the 10-20 system\r\n Name , Z,x,Y\r\n\r\n"
                         "Fp1,-7.5,-29.4,+83.9\r\n\"Cz\",  96.0 ,0,-9.2\r\n# end\r\nO2,1e1,29,-114\r\n");
    const std::vector<io::SensorRow> sensors = io::read_sensors(file);
    ASSERT_EQ(sensors.size(), 3u);
    EXPECT_EQ(sensors[0].name, "Fp1");
    EXPECT_EQ(sensors[0].position_mm, (Vec3{-29.4, 83.9, -7.5}));
    EXPECT_EQ(sensors[0].line, 4u);
    EXPECT_EQ(sensors[1].name, "Cz");
    EXPECT_EQ(sensors[1].position_mm, (Vec3{0, -9.2, 96.0}));
    EXPECT_EQ(sensors[2].position_mm, (Vec3{29, -114, 10}));
    EXPECT_EQ(sensors[2].line, 7u);
}

TEST_F(TableReaders, SensorsWithoutNamesAndWithoutFinalNewline)
{
    const std::vector<io::SensorRow> sensors = io::read_sensors(write("plain.csv", "x,y,z\n1,2,3\n4,5,6"));
    ASSERT_EQ(sensors.size(), 2u);
    EXPECT_TRUE(sensors[1].name.empty());
    EXPECT_EQ(sensors[1].position_mm, (Vec3{4, 5, 6}));
}

TEST_F(TableReaders, SensorDefectsNameTheFileTheLineAndTheFix)
{
    const auto refused = [&](const std::string& name, const std::string& text,
                             std::initializer_list<std::string> parts) {
        expect_refused<IoError>(io::read_sensors, name, text, parts);
    };
    refused("empty.csv", "", {"empty.csv: the file is empty", "x,y,z"});
    refused("blank.csv", "\n  \n# only a comment\n", {"blank.csv: no header line"});
    refused("header-only.csv", "x,y,z\n", {"header-only.csv: no sensors after the header"});
    refused("no-header.csv", "1,2,3\n", {"no-header.csv line 1: the first line is data, not a header", "x,y,z"});
    refused("unknown.csv", "x,y,z,w\n1,2,3,4\n",
            {"unknown.csv line 1: unknown column 'w'", "x,y,z (and optionally name)"});
    refused("missing.csv", "x,z\n1,2\n", {"missing.csv line 1: the header has no column 'y'"});
    refused("twice.csv", "x,y,z,X\n", {"twice.csv line 1: column 'x' appears twice (columns 1 and 4)"});
    refused("short.csv", "x,y,z\n1,2,3\n4,5\n", {"short.csv line 3: 2 fields where the header has 3 columns"});
    refused("cut.csv", "x,y,z\n1,2,", {"cut.csv line 2, column z: '' is not a finite number"});
    refused("word.csv", "x,y,z\n1,two,3\n", {"word.csv line 2, column y: 'two' is not a finite number"});
    refused("nan.csv", "x,y,z\n1,nan,3\n", {"nan.csv line 2, column y: 'nan'"});
    refused("inf.csv", "x,y,z\n1,2,-inf\n", {"inf.csv line 2, column z: '-inf'"});
    refused("overflow.csv", "x,y,z\n1e999,2,3\n", {"overflow.csv line 2, column x: '1e999'"});
    refused("hex.csv", "x,y,z\n0x10,2,3\n", {"hex.csv line 2, column x: '0x10'"});
    refused("plusminus.csv", "x,y,z\n+-1,2,3\n", {"plusminus.csv line 2, column x"});
    refused("binary.csv", std::string("x,y,z\n1,\0\x01\x7f,3\n", 14), {"binary.csv line 2, column y: '\?\?\?'"});
    refused("unnamed.csv", "name,x,y,z\nCz,0,0,1\n,1,2,3\n", {"unnamed.csv line 3: the sensor has no name"});
    refused("same-name.csv", "name,x,y,z\nCz,0,0,1\nCz,1,2,3\n", {"same-name.csv line 3: name 'Cz' is also on line 2"});
    refused("control.csv", "name,x,y,z\nC\tz,0,0,1\n", {"control.csv line 2: the name 'C?z' holds control characters"});
    refused("comma-name.csv", "name,x,y,z\n\"C,z\",0,0,1\n", {"comma-name.csv line 2: 5 fields", "no commas in names"});
}

TEST_F(TableReaders, ElectrodeMontageWithNamesAndSignedCurrents)
{
    const std::string file = write("montage.csv", "name,x,y,z,radius_mm,current_a\n"
                                                  "C3,-52.1,-18.9,96.4,12.5,+0.002\n"
                                                  "Fp2,27.3,88.1,29.0,12.5,-0.002\n"
                                                  "Pz,0,-70,80,5,0\n");
    const std::vector<io::ElectrodeRow> montage = io::read_electrodes(file);
    ASSERT_EQ(montage.size(), 3u);
    EXPECT_EQ(montage[0].name, "C3");
    EXPECT_EQ(montage[0].centre_mm, (Vec3{-52.1, -18.9, 96.4}));
    EXPECT_EQ(montage[0].radius_mm, 12.5);
    EXPECT_EQ(montage[0].current_a, 0.002);
    EXPECT_EQ(montage[1].current_a, -0.002);
    EXPECT_EQ(montage[2].current_a, 0);
    EXPECT_EQ(montage[2].line, 4u);
}

TEST_F(TableReaders, ElectrodeDefectsNameTheFileTheLineAndTheFix)
{
    const auto refused = [&](const std::string& name, const std::string& text,
                             std::initializer_list<std::string> parts) {
        expect_refused<IoError>(io::read_electrodes, name, text, parts);
    };
    refused("ma.csv", "x,y,z,radius_mm,current_ma\n",
            {"ma.csv line 1: unknown column 'current_ma' (give the current in ampere, as current_a)"});
    refused("cm.csv", "x,y,z,radius_cm,current_a\n",
            {"cm.csv line 1: unknown column 'radius_cm' (give the radius in mm, as radius_mm)"});
    refused("sensor-header.csv", "x,y,z\n1,2,3\n", {"sensor-header.csv line 1: the header has no column 'radius_mm'"});
    refused("nan-current.csv", "x,y,z,radius_mm,current_a\n0,0,90,10,NaN\n",
            {"nan-current.csv line 2, column current_a: 'NaN'"});
    expect_refused<InputError>(io::read_electrodes, "negative.csv", "x,y,z,radius_mm,current_a\n0,0,90,-10,0.001\n",
                               {"negative.csv line 2: radius_mm is -10", "positive length in mm"});
    expect_refused<InputError>(io::read_electrodes, "zero.csv",
                               "x,y,z,radius_mm,current_a\n0,0,90,10,1e-3\n0,0,-90,0,-1e-3\n",
                               {"zero.csv line 3: radius_mm is 0"});
    std::string many = "x,y,z,radius_mm,current_a\n";
    for (std::size_t k = 0; k <= io::max_electrodes; ++k) many += "0,0,90,5,0\n";
    refused("many.csv", many, {"many.csv line 10002: more than 10000 electrodes"});
}

TEST_F(TableReaders, HugeFilesAreRefusedBeforeTheyAreRead)
{
    // Sparse files: the size is checked before a byte is read, so these cost nothing.
    const auto huge = [&](const std::string& name, std::uintmax_t bytes) {
        const std::string file = write(name, "x");
        std::filesystem::resize_file(file, bytes);
        return file;
    };
    expect_error<IoError>(
        [&] { (void)io::read_sensors(huge("huge.csv", 3ull << 30)); },
        {"huge.csv: 3221225472 bytes, more than the 67108864 a file of 100000 sensors", "right file"});
    expect_error<IoError>([&] { (void)io::read_electrodes(huge("huge-montage.csv", 65ull << 20)); },
                          {"huge-montage.csv: 68157440 bytes, more than the 67108864 a file of 10000 electrodes"});
    expect_error<IoError>(
        [&] { (void)io::read_conductivity_table(huge("huge.json", io::max_conductivity_table_bytes + 1)); },
        {"huge.json: 1048577 bytes is more than a conductivity table needs"});
}

TEST_F(TableReaders, ConductivityNumbersAndBothTensorShapes)
{
    const std::string file = write("cond.json", R"({"scalp": 0.43, "3": 1.79,
        "white": [[0.65, 0, 0], [0, 0.065, 0], [0, 0, 0.065]], "skull": [0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.002]})");
    const std::map<std::string, Mat3> table = io::read_conductivity_table(file);
    ASSERT_EQ(table.size(), 4u);
    EXPECT_EQ(table.at("scalp"), (Mat3{0.43, 0, 0, 0, 0.43, 0, 0, 0, 0.43}));
    EXPECT_EQ(table.at("3"), (Mat3{1.79, 0, 0, 0, 1.79, 0, 0, 0, 1.79}));
    EXPECT_EQ(table.at("white"), (Mat3{0.65, 0, 0, 0, 0.065, 0, 0, 0, 0.065}));
    EXPECT_EQ(table.at("skull")[8], 0.002);
}

TEST_F(TableReaders, ConductivityDefectsNameTheFileAndTheFix)
{
    const auto read = io::read_conductivity_table;
    expect_refused<IoError>(read, "empty.json", "", {"empty.json: the file is empty", "S/m"});
    expect_refused<IoError>(read, "cut.json", R"({"brain": 0.3)", {"cut.json: not valid JSON", "line 1, column 14"});
    expect_refused<IoError>(read, "array.json", "[0.3]", {"array.json: the table is a JSON array, not an object"});
    expect_refused<IoError>(read, "deep.json", std::string(5000, '[') + std::string(5000, ']'),
                            {"deep.json line 1: nested 4 deep"});
    expect_refused<IoError>(read, "big-number.json", R"({"brain": 1e999})",
                            {"big-number.json: not valid JSON", "1e999"});
    expect_refused<InputError>(read, "none.json", "{}", {"none.json: the table is empty", "leave out --conductivity"});
    expect_refused<InputError>(read, "twice.json", R"({"brain": 0.3, "Brain": 0.2})",
                               {"twice.json: \"brain\" and \"Brain\" name the same tissue; give each tissue once"});
    expect_refused<InputError>(read, "label-twice.json", R"({"3": 0.3, "003": 0.2})",
                               {"\"3\" and \"003\" name the same tissue"});
    expect_refused<InputError>(read, "key.json", R"({"": 0.3})", {"key.json: a key is empty"});
    expect_refused<InputError>(read, "negative.json", R"({"brain": -0.3})",
                               {"negative.json: \"brain\" is -0.3 S/m", "positive"});
    expect_refused<InputError>(read, "zero.json", R"({"brain": 0})", {"\"brain\" is 0 S/m"});
    expect_refused<InputError>(read, "text.json", R"({"brain": "high"})",
                               {"text.json: \"brain\" is neither a number", "found JSON string"});
    expect_refused<InputError>(read, "three.json", R"({"brain": [1, 2, 3]})",
                               {"\"brain\" is neither", "9 finite numbers", "found JSON array"});
    expect_refused<InputError>(read, "ragged.json", R"({"brain": [[1, 0], [0, 1, 0, 0], [0, 0, 1]]})",
                               {"\"brain\" is neither"});
    expect_refused<InputError>(read, "null-entry.json", R"({"brain": [1, 0, 0, 0, 1, 0, 0, 0, null]})",
                               {"\"brain\" is neither"});
}

} // namespace
} // namespace tissuemesh

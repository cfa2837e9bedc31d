// tm-leadfield's files as library readers and writers: source and MEG sensor tables (CSV), and NumPy .npy
// matrices. Each accepted shape reads to the exact values; each defect gives our typed error naming the file.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "io/npy.h"
#include "io/read_electrodes.h"
#include "io/read_meg_sensors.h"
#include "io/read_sources.h"
#include "tests/io/expect_error.h"
#include "tests/io/reader_files.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

using testing::expect_error;

class LeadFieldReaders : public testing::ReaderFiles {};

TEST_F(LeadFieldReaders, SourcesFreeOrOrientedNormalised)
{
    const std::vector<io::SourceRow> free = io::read_sources(write("free.csv", "x,y,z\n1,2,3\n-4,5.5,60\n"));
    ASSERT_EQ(free.size(), 2u);
    EXPECT_FALSE(free[0].orientation);
    EXPECT_EQ(free[1].position_mm, (Vec3{-4, 5.5, 60}));
    EXPECT_EQ(free[1].line, 3u);
    const std::vector<io::SourceRow> oriented =
        io::read_sources(write("oriented.csv", "NZ,x,y,z,nx,ny,name\n4,1,2,3,0,3,s1\n"));
    ASSERT_TRUE(oriented[0].orientation);
    EXPECT_NEAR((*oriented[0].orientation)[1], 0.6, 1e-15);
    EXPECT_NEAR((*oriented[0].orientation)[2], 0.8, 1e-15);
    EXPECT_EQ(oriented[0].name, "s1");
    expect_error<IoError>([&] { io::read_sources(write("partial.csv", "x,y,z,nx,ny,nz\n1,2,3,0,,1\n")); },
                          {"partial.csv line 2: 2 of the orientation's nx,ny,nz given"});
    expect_error<IoError>([&] { io::read_sources(write("mixed.csv", "x,y,z,nx,ny,nz\n1,2,3,0,0,1\n1,2,3,,,\n")); },
                          {"mixed.csv line 3: no orientation where line 2 has one"});
    expect_error<InputError>([&] { io::read_sources(write("zero.csv", "x,y,z,nx,ny,nz\n1,2,3,0,0,0\n")); },
                             {"zero.csv line 2: the orientation (0, 0, 0) has no direction"});
    expect_error<IoError>([&] { io::read_sources(write("unknown.csv", "x,y,z,px\n1,2,3,4\n")); },
                          {"unknown column 'px'", "x,y,z (and optionally nx,ny,nz, name)"});
}

TEST_F(LeadFieldReaders, MegSensorsMagnetometersAndGradiometers)
{
    const std::vector<io::MegSensorRow> sensors = io::read_meg_sensors(
        write("meg.csv", "name,x,y,z,nx,ny,nz,x2,y2,z2\nMEG0111,0,0,102,0,0,2,,,\nMEG0112,0,102,0,1,0,0,0,104,0\n"));
    ASSERT_EQ(sensors.size(), 2u);
    EXPECT_EQ(sensors[0].normal, (Vec3{0, 0, 1}));
    EXPECT_FALSE(sensors[0].second_coil_mm);
    EXPECT_EQ(*sensors[1].second_coil_mm, (Vec3{0, 104, 0}));
    EXPECT_EQ(io::read_meg_sensors(write("plain.csv", "x,y,z,nx,ny,nz\n0,0,100,0,0,1\n")).size(), 1u);
    expect_error<IoError>([&] { io::read_meg_sensors(write("no-normal.csv", "x,y,z\n0,0,100\n")); },
                          {"no-normal.csv line 1: the header has no column 'nx'"});
    expect_error<InputError>([&] { io::read_meg_sensors(write("flat.csv", "x,y,z,nx,ny,nz\n0,0,100,0,0,0\n")); },
                             {"flat.csv line 2: the normal (0, 0, 0) has no direction"});
    expect_error<IoError>(
        [&] { io::read_meg_sensors(write("half.csv", "x,y,z,nx,ny,nz,x2,y2,z2\n0,0,100,0,0,1,1,,\n")); },
        {"half.csv line 2: 1 of the second coil's x2,y2,z2 given"});
    expect_error<InputError>(
        [&] { io::read_meg_sensors(write("same.csv", "x,y,z,nx,ny,nz,x2,y2,z2\n0,0,100,0,0,1,0,0,100\n")); },
        {"same.csv line 2: the second coil is on the first"});
}

// tm-leadfield's tDCS electrodes need no current; tm-solve's montages still do.
TEST_F(LeadFieldReaders, ElectrodesWithoutCurrentsOnlyWhereAllowed)
{
    const std::string file = write("cap.csv", "name,x,y,z,radius_mm\nT7,-92,0,0,15\n");
    EXPECT_EQ(io::read_electrode_patches(file).front().current_a, 0.0);
    expect_error<IoError>([&] { io::read_electrodes(file); }, {"cap.csv line 1: the header has no column 'current_a'"});
}

// A matrix written and read back is the same matrix; NumPy's file layout: magic, version 1.0, a header
// padded to a multiple of 64 bytes (with the 10 of magic, version and length: 128 here) and ended by a newline,
// then the little-endian doubles.
TEST_F(LeadFieldReaders, NpyRoundTripAndLayout)
{
    const io::NpyMatrix matrix{2, 3, {1.5, -2, 3e-300, 4, 5, std::nextafter(6.0, 7.0)}};
    const std::string file = (dir_.path() / "m.npy").string();
    io::write_npy(file, matrix);
    const io::NpyMatrix back = io::read_npy(file);
    EXPECT_EQ(back.rows, 2u);
    EXPECT_EQ(back.columns, 3u);
    EXPECT_EQ(back.values, matrix.values);
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_EQ(bytes.size(), 128u + 48u);
    EXPECT_EQ(bytes.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
    EXPECT_EQ(bytes[127], '\n');
    EXPECT_EQ(bytes.substr(8, 2), std::string("\x76\x00", 2)); // 118 bytes of dictionary
    EXPECT_NE(bytes.find("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }"), std::string::npos);
    EXPECT_THROW(io::write_npy(file, {2, 2, {1, 2, 3}}), InputError);
}

// What NumPy writes in its other ways: Fortran order, a 1-D shape, version 2.0; and what is refused.
TEST_F(LeadFieldReaders, NpyVariantsAndDefects)
{
    const auto npy = [](const std::string& dictionary, const std::string& data, char major = 1) {
        std::string header = dictionary;
        const std::size_t preamble = major == 1 ? 10 : 12;
        header.append((64 - (preamble + header.size() + 1) % 64) % 64, ' ');
        header += '\n';
        std::string bytes = std::string("\x93NUMPY", 6) + major + '\0';
        const std::size_t n = header.size();
        bytes += static_cast<char>(n & 0xff);
        bytes += static_cast<char>(n >> 8);
        if (major != 1) bytes += std::string(2, '\0');
        return bytes + header + data;
    };
    const double values[4] = {1, 2, 3, 4};
    const std::string four(reinterpret_cast<const char*>(values), 32);
    const io::NpyMatrix fortran =
        io::read_npy(write("f.npy", npy("{'descr': '<f8', 'fortran_order': True, 'shape': (2, 2), }", four)));
    EXPECT_EQ(fortran.values, (std::vector<double>{1, 3, 2, 4}));
    const io::NpyMatrix vector =
        io::read_npy(write("v.npy", npy("{'shape': (4,), 'fortran_order': False, 'descr': '<f8'}", four, 2)));
    EXPECT_EQ(vector.rows, 4u);
    EXPECT_EQ(vector.columns, 1u);
    expect_error<IoError>([&] { io::read_npy(write("text.npy", "x,y,z\n")); }, {"text.npy: not a NumPy .npy file"});
    expect_error<IoError>(
        [&] {
            io::read_npy(write("f4.npy", npy("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 2), }", four)));
        },
        {"f4.npy: the values are '<f4', not little-endian float64"});
    expect_error<IoError>(
        [&] {
            io::read_npy(write("cut.npy", npy("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }", four)));
        },
        {"cut.npy: the header says 2 x 3 values but the file holds 32 bytes"});
    expect_error<IoError>(
        [&] {
            io::read_npy(
                write("huge.npy",
                      npy("{'descr': '<f8', 'fortran_order': False, 'shape': (1, 2305843009213693952), }", four)));
        },
        {"huge.npy: the header says 1 x 2305843009213693952 values"});
    expect_error<IoError>(
        [&] {
            io::read_npy(
                write("cube.npy", npy("{'descr': '<f8', 'fortran_order': False, 'shape': (1, 2, 2), }", four)));
        },
        {"cube.npy: the shape (1, 2, 2) has 3 dimensions"});
    expect_error<IoError>(
        [&] { io::read_npy(write("short.npy", std::string("\x93NUMPY\x01\x00\x40\x00{'descr'", 17))); },
        {"short.npy: truncated .npy header"});
}

} // namespace
} // namespace tissuemesh

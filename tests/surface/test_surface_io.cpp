// Round trips and bad input for write_surface / read_surface (io/surface_io.h).
#include <cstring>
#include <fstream>
#include <gtest/gtest.h>

#include "core/error.h"
#include "io/surface_io.h"
#include "surface/extract_interfaces.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

using testing::TempDir;

/// Three tissues meeting along a line, with names: junctions, several patches, both side orders.
InterfaceComplex sample_complex()
{
    LabelImage image({4, 4, 3}, {0.7, 1.1, 1.3}, {-3.25, 8.5, 1e3});
    for (std::size_t k = 0; k < 3; ++k)
        for (std::size_t j = 0; j < 4; ++j)
            for (std::size_t i = 0; i < 4; ++i) image.at(i, j, k) = static_cast<Label>(i < 2 ? 1 : (j < 2 ? 2 : 300));
    image.names() = {{1, "scalp"}, {2, "grey matter"}, {300, "CSF"}};
    return surface::extract_interfaces(image);
}

void write_bytes(const std::filesystem::path& path, const std::string& bytes)
{
    std::ofstream out(path, std::ios::binary);
    out << bytes;
}

std::string read_bytes(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(SurfaceIo, PlyAndVtpKeepGeometryAndLabelPairsExactly)
{
    const InterfaceComplex complex = sample_complex();
    TempDir dir;
    for (const std::string name : {"c.ply", "c.vtp"}) {
        io::write_surface(complex, dir / name);
        const InterfaceComplex back = io::read_surface(dir / name);
        ASSERT_EQ(back.vertices.size(), complex.vertices.size()) << name;
        EXPECT_EQ(back.vertices, complex.vertices) << name << ": float64 (ply) and %.17g (vtp) are exact";
        EXPECT_EQ(back.triangles, complex.triangles) << name;
        EXPECT_EQ(back.sides, complex.sides) << name;
    }
    const InterfaceComplex ply = io::read_surface(dir / "c.ply");
    EXPECT_EQ(ply.names, complex.names) << "names travel as 'comment tissue' lines, spaces included";
}

TEST(SurfaceIo, OffAndStlKeepGeometry)
{
    const InterfaceComplex complex = sample_complex();
    TempDir dir;
    io::write_surface(complex, dir / "c.off");
    const InterfaceComplex off = io::read_surface(dir / "c.off");
    EXPECT_EQ(off.vertices, complex.vertices);
    EXPECT_EQ(off.triangles, complex.triangles);
    for (const LabelPair& side : off.sides) EXPECT_EQ(side, (LabelPair{1, 0})) << "geometry only";

    io::write_surface(complex, dir / "c.stl");
    const InterfaceComplex stl = io::read_surface(dir / "c.stl");
    // STL stores float32 corners per triangle; reading welds identical corners back together, so the
    // vertex count returns and every corner is within float32 rounding (~1e-4 mm at 1000 mm).
    EXPECT_EQ(stl.vertices.size(), complex.vertices.size());
    ASSERT_EQ(stl.triangles.size(), complex.triangles.size());
    for (std::size_t t = 0; t < stl.triangles.size(); ++t)
        for (int c = 0; c < 3; ++c)
            EXPECT_LT(distance(stl.vertices[stl.triangles[t][c]], complex.vertices[complex.triangles[t][c]]), 1e-3);
}

TEST(SurfaceIo, ReadsAsciiPlyWithoutLabels)
{
    TempDir dir;
    write_bytes(dir / "a.ply",
                "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 4\nproperty float x\n"
                "property float y\nproperty float z\nelement face 4\nproperty list uchar int vertex_index\n"
                "end_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    const InterfaceComplex tet = io::read_surface(dir / "a.ply");
    EXPECT_EQ(tet.vertices.size(), 4u);
    ASSERT_EQ(tet.triangles.size(), 4u);
    EXPECT_EQ(tet.triangles[3], (Triangle{1, 2, 3}));
    EXPECT_EQ(tet.sides[0], (LabelPair{1, 0}));
}

TEST(SurfaceIo, ReadsBigEndianBinaryPly)
{
    // One triangle, vertices as big-endian float32, indices int32, labels uchar.
    std::string bytes = "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                        "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                        "property uchar label_a\nproperty uchar label_b\nend_header\n";
    const auto put_be = [&bytes](std::uint32_t word) {
        for (int shift = 24; shift >= 0; shift -= 8) bytes += static_cast<char>(word >> shift & 0xff);
    };
    const float coordinates[9] = {0, 0, 0, 2, 0, 0, 0, 3, 0};
    for (const float c : coordinates) {
        std::uint32_t word = 0;
        std::memcpy(&word, &c, 4);
        put_be(word);
    }
    bytes += '\x03';
    for (std::uint32_t index : {0u, 1u, 2u}) put_be(index);
    bytes += '\x04';
    bytes += '\x02';
    TempDir dir;
    write_bytes(dir / "be.ply", bytes);
    const InterfaceComplex complex = io::read_surface(dir / "be.ply");
    ASSERT_EQ(complex.triangles.size(), 1u);
    EXPECT_EQ(complex.vertices[2], (Vec3{0, 3, 0}));
    EXPECT_EQ(complex.sides[0], (LabelPair{4, 2}));
}

TEST(SurfaceIo, SameComplexSameBytes)
{
    TempDir dir;
    io::write_surface(sample_complex(), dir / "a.ply");
    io::write_surface(sample_complex(), dir / "b.ply");
    EXPECT_EQ(read_bytes(dir / "a.ply"), read_bytes(dir / "b.ply")) << "extraction and writing are deterministic";
}

/// Reading `bytes` as `name` must throw `Expected` with a one-line message naming the file and `hint`.
template <typename Expected>
void expect_rejected(const std::string& name, const std::string& bytes, const std::string& hint)
{
    TempDir dir;
    write_bytes(dir / name, bytes);
    try {
        io::read_surface(dir / name);
        ADD_FAILURE() << name << " was accepted";
    } catch (const Expected& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find(name), std::string::npos) << message;
        EXPECT_NE(message.find(hint), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

TEST(SurfaceIo, RejectsBrokenFilesWithOneLineMessages)
{
    TempDir dir;
    io::write_surface(sample_complex(), dir / "good.ply");
    io::write_surface(sample_complex(), dir / "good.stl");
    io::write_surface(sample_complex(), dir / "good.vtp");
    const std::string ply = read_bytes(dir / "good.ply");
    expect_rejected<IoError>("cut.ply", ply.substr(0, ply.size() - 7), "truncated");
    expect_rejected<IoError>("magic.ply", "plx\n" + ply.substr(4), "not a PLY file");
    const std::string stl = read_bytes(dir / "good.stl");
    expect_rejected<IoError>("cut.stl", stl.substr(0, stl.size() - 1), "truncated");
    const std::string vtp = read_bytes(dir / "good.vtp");
    expect_rejected<IoError>("cut.vtp", vtp.substr(0, vtp.size() / 2), "truncated");
    expect_rejected<IoError>("magic.off", "NOFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "not an OFF file");
    expect_rejected<IoError>("cut.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n", "truncated");
    expect_rejected<InputError>("dangling.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", "refers to vertex 7");
    expect_rejected<InputError>("nan.off", "OFF\n3 1 0\n0 0 nan\n1 0 0\n0 1 0\n3 0 1 2\n", "non-finite");
    expect_rejected<IoError>("quad.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n", "only triangles");
    expect_rejected<IoError>("empty.stl", "", "too short");
    EXPECT_THROW(io::read_surface(dir / "missing.ply"), IoError);
    EXPECT_THROW(io::write_surface(sample_complex(), dir / "c.xyz"), IoError);
    EXPECT_THROW(io::write_surface(sample_complex(), dir / "no-such-dir" / "c.ply"), IoError);
    EXPECT_EQ(dir.files(), (std::vector<std::string>{"good.ply", "good.stl", "good.vtp"})) << "nothing half-written";
}

} // namespace
} // namespace tissuemesh

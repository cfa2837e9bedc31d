// write_surface_streamed(): a complex streamed from extract_interfaces() into a PLY file gives the very
// bytes write_surface() gives for the whole complex, and failures leave no file behind.
#include <fstream>
#include <gtest/gtest.h>

#include "core/error.h"
#include "image/phantom.h"
#include "io/surface_io.h"
#include "io/write_surface_streamed.h"
#include "surface/extract_interfaces.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

using testing::TempDir;

std::string read_bytes(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(StreamedPly, SameBytesAsWritingTheWholeComplex)
{
    const struct {
        const char* phantom;
        std::map<Label, int> priority;
    } cases[] = {{"junction", {}}, {"thin", {{1, 1}}}, {"spheres4", {}}};
    TempDir dir;
    for (const auto& c : cases) {
        const image::Phantom phantom = image::make_phantom(c.phantom, {.voxel_mm = 2.0});
        const surface::ExtractOptions options{.priority = c.priority};
        io::write_surface(surface::extract_interfaces(phantom.image, options), dir / "whole.ply");
        io::write_surface_streamed(dir / "streamed.ply", [&](InterfaceSink& sink) {
            surface::extract_interfaces(phantom.image, options, sink);
        });
        const std::string whole = read_bytes(dir / "whole.ply");
        ASSERT_GT(whole.size(), 1000u) << c.phantom;
        EXPECT_TRUE(read_bytes(dir / "streamed.ply") == whole) << c.phantom << ": the bytes differ";
        EXPECT_EQ(dir.files(), (std::vector<std::string>{"streamed.ply", "whole.ply"})) << "side files removed";
    }
}

TEST(StreamedPly, FailuresLeaveNothingBehind)
{
    TempDir dir;
    const std::vector<Vec3> points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const std::vector<Triangle> good{{0, 1, 2}}, dangling{{0, 1, 3}};
    const std::vector<LabelPair> sides{{1, 0}};
    const auto expect_failure = [&](const std::function<void(InterfaceSink&)>& produce, const std::string& hint) {
        try {
            io::write_surface_streamed(dir / "out.ply", produce);
            ADD_FAILURE() << "no error for " << hint;
        } catch (const Error& error) {
            EXPECT_NE(std::string(error.what()).find(hint), std::string::npos) << error.what();
        }
        EXPECT_TRUE(dir.files().empty()) << hint << ": no output, temporary or side file is left";
    };
    // The producer fails half way: the pieces already written are discarded.
    expect_failure(
        [&](InterfaceSink& sink) {
            sink.add({0, points, good, sides});
            throw AlgorithmError("the producer gave up");
        },
        "the producer gave up");
    expect_failure(
        [&](InterfaceSink& sink) {
            sink.add({0, points, dangling, sides});
        },
        "out.ply: triangle 0 refers to vertex 3 but only 3 vertices came before it");
    try {
        io::write_surface_streamed(dir / "out.stl", [](InterfaceSink&) {});
        ADD_FAILURE() << "a streamed .stl was accepted";
    } catch (const IoError& error) {
        EXPECT_NE(std::string(error.what()).find("supports .ply only"), std::string::npos) << error.what();
    }
    EXPECT_TRUE(dir.files().empty());
}

TEST(StreamedPly, AnEmptyStreamIsAValidEmptyComplex)
{
    TempDir dir;
    io::write_surface_streamed(dir / "empty.ply", [](InterfaceSink& sink) { sink.start({{3, "csf"}}, 7); });
    const InterfaceComplex back = io::read_surface(dir / "empty.ply");
    EXPECT_EQ(back.vertex_count(), 0u);
    EXPECT_EQ(back.triangle_count(), 0u);
    EXPECT_EQ(back.names.at(3), "csf");
    EXPECT_EQ(back.background, 7);
}

} // namespace
} // namespace tissuemesh

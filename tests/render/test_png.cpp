// PNG writing and reading: exact round trips, and damaged files refused with a message.
#include <gtest/gtest.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "render/png.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

render::Canvas pattern(std::size_t width, std::size_t height)
{
    render::Canvas canvas(width, height);
    for (std::size_t y = 0; y < height; ++y)
        for (std::size_t x = 0; x < width; ++x)
            canvas.set(static_cast<long>(x), static_cast<long>(y),
                       {static_cast<std::uint8_t>(x * 7 + y), static_cast<std::uint8_t>(x * y % 251),
                        static_cast<std::uint8_t>(255 - y)});
    return canvas;
}

TEST(Png, RoundTripKeepsEveryPixel)
{
    const render::Canvas canvas = pattern(37, 23);
    const std::string bytes = render::encode_png(canvas);
    EXPECT_EQ(bytes.substr(1, 3), "PNG");
    const render::Canvas back = render::decode_png(bytes);
    ASSERT_EQ(back.width(), 37u);
    ASSERT_EQ(back.height(), 23u);
    EXPECT_EQ(back.pixels(), canvas.pixels());
    EXPECT_EQ(render::encode_png(back), bytes); // deterministic bytes
}

TEST(Png, WritesAtomicallyAndReadsBack)
{
    testing::TempDir dir;
    const render::Canvas canvas = pattern(5, 300);
    render::write_png(canvas, dir / "p.png");
    EXPECT_EQ(dir.files(), std::vector<std::string>{"p.png"});
    EXPECT_EQ(render::decode_png(read_file_bytes(dir / "p.png")).pixels(), canvas.pixels());
}

TEST(Png, DamagedBytesAreRefusedWithTheReason)
{
    std::string bytes = render::encode_png(pattern(8, 8));
    std::string flipped = bytes;
    flipped[45] =
        static_cast<char>(flipped[45] ^ 0x10); // IDAT starts at byte 33: its data, so its CRC no longer matches
    try {
        render::decode_png(flipped, "picture.png");
        FAIL() << "a damaged PNG was accepted";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("picture.png: CRC of PNG chunk IDAT"), std::string::npos) << e.what();
    }
    EXPECT_THROW(render::decode_png("GIF89a....", "x.gif"), IoError);
    EXPECT_THROW(render::decode_png(bytes.substr(0, bytes.size() - 20), "cut.png"), IoError);
}

TEST(Canvas, TriangleKeepsTheNearerOfTwoOverlaps)
{
    render::Canvas canvas(20, 20);
    // Far red, then near blue over the same square: blue wins; drawn the other way round, blue still wins.
    canvas.draw_triangle({0, 0, 5}, {20, 0, 5}, {0, 20, 5}, {255, 0, 0});
    canvas.draw_triangle({0, 0, 1}, {20, 0, 1}, {0, 20, 1}, {0, 0, 255});
    canvas.draw_triangle({0, 0, 9}, {20, 0, 9}, {0, 20, 9}, {0, 255, 0});
    EXPECT_EQ(canvas.at(3, 3), (render::Rgb{0, 0, 255}));
    EXPECT_EQ(canvas.at(18, 18), (render::Rgb{255, 255, 255})); // outside the triangle
    EXPECT_THROW(render::Canvas(0, 10), InputError);
}

} // namespace
} // namespace tissuemesh

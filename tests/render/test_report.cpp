// report.html: every tissue, every picture (decodable from its data URI), every step with its time.
#include <fstream>
#include <gtest/gtest.h>

#include "core/error.h"
#include "render/png.h"
#include "render/report_html.h"
#include "tests/support/cli.h"

namespace tissuemesh {
namespace {

std::string unbase64(const std::string& text)
{
    static const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::uint32_t group = 0;
    int bits = 0;
    for (const char c : text) {
        if (c == '=') break;
        group = group << 6 | static_cast<std::uint32_t>(alphabet.find(c));
        bits += 6;
        if (bits >= 8) bits -= 8, out.push_back(static_cast<char>((group >> bits) & 0xFF));
    }
    return out;
}

std::size_t occurrences(const std::string& text, const std::string& part)
{
    std::size_t count = 0;
    for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++count;
    return count;
}

TEST(Report, Base64OfTheRfcVectors)
{
    EXPECT_EQ(render::base64(""), "");
    EXPECT_EQ(render::base64("f"), "Zg==");
    EXPECT_EQ(render::base64("fo"), "Zm8=");
    EXPECT_EQ(render::base64("foobar"), "Zm9vYmFy");
}

TEST(Report, HoldsEveryTissuePictureAndStep)
{
    render::Canvas canvas(6, 4, {10, 200, 30});
    render::ReportContent content;
    content.title = "sphere <head>";
    content.pictures = {{"surface", render::encode_png(canvas)}, {"section", render::encode_png(render::Canvas(3, 3))}};
    content.steps = {{"tetra", {{"tool", "tm-tetra"}, {"status", "ok"}, {"seconds", 2.5}, {"tets", 1234}}},
                     {"assess",
                      {{"tool", "tm-assess"},
                       {"status", "ok"},
                       {"seconds", 1.5},
                       {"tissues",
                        {{"1", {{"name", "scalp"}, {"dice", 0.98765}, {"mesh_volume_mm3", 157114.9}}},
                         {"4", {{"name", "brain"}, {"dice", 1.0}}}}}}}};
    const std::string html = render::report_html(content);
    EXPECT_NE(html.find("<title>sphere &lt;head&gt;</title>"), std::string::npos);
    for (const char* text : {"scalp", "brain", "0.9877", "157114.9", "tm-tetra", "tets 1234"})
        EXPECT_NE(html.find(text), std::string::npos) << text;
    EXPECT_NE(html.find("<th>total</th><th></th><th></th><th>4</th>"), std::string::npos); // 2.5 + 1.5 s
    EXPECT_EQ(occurrences(html, "data:image/png;base64,"), 2u);
    const std::size_t start = html.find("base64,") + 7;
    const std::string png = unbase64(html.substr(start, html.find('"', start) - start));
    EXPECT_EQ(render::decode_png(png).pixels(), canvas.pixels());
    EXPECT_EQ(html.find("http"), std::string::npos); // nothing to fetch
}

TEST(Report, CollectsSummariesInPipelineOrderAndRefusesAnEmptyFolder)
{
    testing::TempDir dir;
    try {
        render::collect_report(dir.path());
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("no tool summary"), std::string::npos) << e.what();
    }
    for (const auto& [name, tool] :
         std::vector<std::pair<std::string, std::string>>{{"a", "tm-solve"}, {"b", "tm-extract"}, {"c", "tm-tetra"}})
        std::ofstream(dir / (name + ".json")) << nlohmann::json{{"tool", tool}, {"seconds", 1}}.dump();
    std::ofstream(dir / "names.json") << R"({"1": "scalp"})"; // not a summary
    render::write_png(render::Canvas(2, 2), dir / "p.png");
    const render::ReportContent content = render::collect_report(dir.path());
    ASSERT_EQ(content.steps.size(), 3u);
    EXPECT_EQ(content.steps[0].name, "b");
    EXPECT_EQ(content.steps[1].name, "c");
    EXPECT_EQ(content.steps[2].name, "a");
    ASSERT_EQ(content.pictures.size(), 1u);
    std::ofstream(dir / "bad.json") << "{";
    EXPECT_THROW(render::collect_report(dir.path()), IoError);
}

} // namespace
} // namespace tissuemesh

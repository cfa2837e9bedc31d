#include "render/tissue_colours.h"

#include <algorithm>
#include <array>

namespace tissuemesh::render {

Rgb tissue_colour(Label label)
{
    static constexpr std::array<Rgb, 16> table{{{225, 175, 140},
                                                {215, 195, 120},
                                                {70, 140, 230},
                                                {225, 105, 120},
                                                {160, 100, 200},
                                                {80, 170, 80},
                                                {150, 50, 40},
                                                {240, 150, 30},
                                                {40, 175, 175},
                                                {130, 90, 50},
                                                {130, 130, 240},
                                                {165, 190, 50},
                                                {215, 60, 175},
                                                {110, 150, 120},
                                                {40, 70, 150},
                                                {235, 215, 60}}};
    if (label == 0) return {64, 64, 64};
    return table[(label - 1u) % table.size()];
}

std::vector<LegendEntry> tissue_legend(const std::vector<Label>& labels, const TissueNames& names)
{
    std::vector<LegendEntry> entries;
    for (const Label label : labels) {
        const auto name = names.find(label);
        std::string text = std::to_string(label);
        if (name != names.end()) text += " " + name->second;
        entries.push_back({tissue_colour(label), text});
    }
    return entries;
}

long draw_legend(Canvas& canvas, long x, long y, const std::vector<LegendEntry>& entries, int scale)
{
    if (entries.empty()) return 0;
    const long line = 10 * scale, box = 7 * scale, pad = 3 * scale;
    long text_width = 0;
    for (const LegendEntry& entry : entries) text_width = std::max(text_width, Canvas::text_width(entry.text, scale));
    const long height = pad * 2 + line * static_cast<long>(entries.size()) - (line - box);
    canvas.fill_rect(x, y, x + 2 * pad + box + pad + text_width, y + height, {255, 255, 255});
    long row = y + pad;
    for (const LegendEntry& entry : entries) {
        canvas.fill_rect(x + pad, row, x + pad + box, row + box, entry.colour);
        canvas.draw_text(x + 2 * pad + box, row, entry.text, {0, 0, 0}, scale);
        row += line;
    }
    return height;
}

} // namespace tissuemesh::render

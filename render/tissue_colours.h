// The fixed per-tissue colour table of every picture, and the legend drawn from it.
#pragma once

#include <string>
#include <vector>

#include "core/label_image.h"
#include "render/canvas.h"

namespace tissuemesh::render {

/// The colour of tissue `label`: label 0 (background) dark grey (64, 64, 64); labels 1..16 from this
/// table, chosen so that the sphere head (1 scalp, 2 skull, 3 CSF, 4 brain) looks familiar; label 17 and
/// up repeat it (label 17 as 1, ...):
///   1 skin (225, 175, 140)   2 bone (215, 195, 120)  3 blue (70, 140, 230)    4 pink (225, 105, 120)
///   5 purple (160, 100, 200) 6 green (80, 170, 80)   7 brick (150, 50, 40)    8 orange (240, 150, 30)
///   9 teal (40, 175, 175)   10 brown (130, 90, 50)  11 lavender (130, 130, 240) 12 olive (165, 190, 50)
///  13 magenta (215, 60, 175) 14 sage (110, 150, 120) 15 navy (40, 70, 150) 16 yellow (235, 215, 60)
/// No two of 1..16 are multiples of each other, so a shaded pixel (colour x light) still names its tissue.
Rgb tissue_colour(Label label);

/// The colour of error volume in the section view: pure red (255, 0, 0).
inline constexpr Rgb error_colour{255, 0, 0};

/// One legend line: a colour box and a text.
struct LegendEntry {
    Rgb colour;
    std::string text;
};

/// The legend entries of `labels` ("1 scalp"), names from `names` (the number alone when absent).
std::vector<LegendEntry> tissue_legend(const std::vector<Label>& labels, const TissueNames& names);

/// Draws `entries` from (x, y) downwards on a white box; returns the box height in px.
long draw_legend(Canvas& canvas, long x, long y, const std::vector<LegendEntry>& entries, int scale = 2);

} // namespace tissuemesh::render

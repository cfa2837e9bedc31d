// The built-in 5 x 7 bitmap font of Canvas::draw_text (our own glyphs).
#pragma once

#include <array>
#include <cstdint>

namespace tissuemesh::render::detail {

/// Seven rows, top first; bit 4 is the leftmost of five columns. Lower case maps to capitals; a
/// character without a glyph gives a hollow box.
const std::array<std::uint8_t, 7>& glyph(char c);

} // namespace tissuemesh::render::detail

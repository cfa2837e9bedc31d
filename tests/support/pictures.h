// Test helpers for pictures: which tissue colours a rendered (or decoded) picture shows.
#pragma once

#include <cstddef>
#include <filesystem>

#include "render/canvas.h"

namespace tissuemesh::testing {

/// Pixels equal to `colour` x s for some shade s in [min_shade, 1], each channel within 3 of it (the
/// surface view shades by multiplying; cut faces and legends show s = 1).
std::size_t count_shaded(const render::Canvas& picture, const render::Rgb& colour, double min_shade = 0.3);

/// Pixels exactly equal to `colour`.
std::size_t count_exact(const render::Canvas& picture, const render::Rgb& colour);

/// Reads and decodes a PNG file with render::decode_png (our own decoder, CRCs checked).
render::Canvas read_png(const std::filesystem::path& path);

} // namespace tissuemesh::testing

// PNG files of canvases: 8-bit RGB, written with zlib (deflate, crc32), read back for tests and reports.
#pragma once

#include <filesystem>
#include <string>

#include "render/canvas.h"

namespace tissuemesh::render {

/// The PNG file (signature, IHDR, one IDAT, IEND) of `canvas` as bytes: colour type 2 (RGB), 8 bits,
/// filter 0 on every row, deflate level 6. Deterministic bytes for the same pixels.
std::string encode_png(const Canvas& canvas);

/// Writes encode_png(canvas) to `path` atomically.
/// @throws IoError when the file cannot be written
void write_png(const Canvas& canvas, const std::filesystem::path& path);

/// Decodes an 8-bit RGB or RGBA, non-interlaced PNG (any of the five row filters), checking every
/// chunk's CRC; alpha is dropped. `what` names the source in messages.
/// @throws IoError when the bytes are not such a PNG (bad signature, CRC, size or compressed data)
Canvas decode_png(const std::string& bytes, const std::string& what = "PNG");

} // namespace tissuemesh::render

#include "render/png.h"

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <vector>

#include <zlib.h>

#include "core/atomic_file.h"
#include "core/error.h"

namespace tissuemesh::render {
namespace {

constexpr char signature[] = "\x89PNG\r\n\x1a\n";

void put_u32(std::string& out, std::uint32_t value)
{
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>((value >> shift) & 0xFF));
}

std::uint32_t get_u32(const std::string& bytes, std::size_t at)
{
    std::uint32_t value = 0;
    for (std::size_t i = 0; i < 4; ++i) value = (value << 8) | static_cast<unsigned char>(bytes[at + i]);
    return value;
}

std::uint32_t chunk_crc(const std::string& type_and_data)
{
    return static_cast<std::uint32_t>(
        crc32(0L, reinterpret_cast<const Bytef*>(type_and_data.data()), static_cast<uInt>(type_and_data.size())));
}

void put_chunk(std::string& out, const std::string& type, const std::string& data)
{
    put_u32(out, static_cast<std::uint32_t>(data.size()));
    const std::string body = type + data;
    out += body;
    put_u32(out, chunk_crc(body));
}

int paeth(int a, int b, int c)
{
    const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

/// Undoes the row filters in place: `data` holds height rows of 1 filter byte + stride bytes.
void unfilter(std::vector<unsigned char>& data, std::size_t stride, std::size_t height, std::size_t bpp,
              const std::string& what)
{
    for (std::size_t y = 0; y < height; ++y) {
        unsigned char* row = &data[y * (stride + 1)];
        const unsigned char* previous = y > 0 ? &data[(y - 1) * (stride + 1) + 1] : nullptr;
        const int filter = row[0];
        unsigned char* pixels = row + 1;
        for (std::size_t i = 0; i < stride; ++i) {
            const int a = i >= bpp ? pixels[i - bpp] : 0, b = previous ? previous[i] : 0;
            const int c = previous && i >= bpp ? previous[i - bpp] : 0;
            int predicted = 0;
            switch (filter) {
            case 0: break;
            case 1: predicted = a; break;
            case 2: predicted = b; break;
            case 3: predicted = (a + b) / 2; break;
            case 4: predicted = paeth(a, b, c); break;
            default: throw IoError(concat(what, ": row ", y, " has unknown PNG filter ", filter));
            }
            pixels[i] = static_cast<unsigned char>(pixels[i] + predicted);
        }
    }
}

} // namespace

std::string encode_png(const Canvas& canvas)
{
    const std::size_t stride = 3 * canvas.width();
    std::string raw;
    raw.reserve((stride + 1) * canvas.height());
    for (std::size_t y = 0; y < canvas.height(); ++y) {
        raw.push_back('\0'); // filter 0 (none)
        for (std::size_t x = 0; x < canvas.width(); ++x)
            for (const std::uint8_t channel : canvas.at(x, y)) raw.push_back(static_cast<char>(channel));
    }
    uLongf packed_size = compressBound(static_cast<uLong>(raw.size()));
    std::string packed(packed_size, '\0');
    if (compress2(reinterpret_cast<Bytef*>(packed.data()), &packed_size, reinterpret_cast<const Bytef*>(raw.data()),
                  static_cast<uLong>(raw.size()), 6) != Z_OK)
        throw IoError("PNG: zlib could not compress the picture");
    packed.resize(packed_size);

    std::string header;
    put_u32(header, static_cast<std::uint32_t>(canvas.width()));
    put_u32(header, static_cast<std::uint32_t>(canvas.height()));
    header += std::string{'\x08', '\x02', '\0', '\0', '\0'}; // 8 bits, RGB, deflate, filter set 0, no interlace
    std::string out(signature, 8);
    put_chunk(out, "IHDR", header);
    put_chunk(out, "IDAT", packed);
    put_chunk(out, "IEND", "");
    return out;
}

void write_png(const Canvas& canvas, const std::filesystem::path& path)
{
    write_text_atomically(path, encode_png(canvas));
}

Canvas decode_png(const std::string& bytes, const std::string& what)
{
    if (bytes.size() < 8 || bytes.compare(0, 8, std::string(signature, 8)) != 0)
        throw IoError(concat(what, ": not a PNG file (bad signature)"));
    std::size_t width = 0, height = 0, channels = 0;
    std::string packed;
    bool ended = false;
    for (std::size_t at = 8; at < bytes.size() && !ended;) {
        if (at + 12 > bytes.size()) throw IoError(concat(what, ": PNG chunk header cut at byte ", at));
        const std::uint32_t length = get_u32(bytes, at);
        if (length > bytes.size() - at - 12)
            throw IoError(concat(what, ": PNG chunk at byte ", at, " runs past the end"));
        const std::string body = bytes.substr(at + 4, 4 + length), type = body.substr(0, 4), data = body.substr(4);
        if (get_u32(bytes, at + 8 + length) != chunk_crc(body))
            throw IoError(concat(what, ": CRC of PNG chunk ", type, " at byte ", at, " is wrong (damaged file)"));
        if (type == "IHDR") {
            if (length != 13) throw IoError(concat(what, ": IHDR has ", length, " bytes, not 13"));
            width = get_u32(data, 0), height = get_u32(data, 4);
            const int depth = static_cast<unsigned char>(data[8]), colour = static_cast<unsigned char>(data[9]);
            if (depth != 8 || (colour != 2 && colour != 6) || data[12] != 0)
                throw IoError(concat(what, ": only 8-bit RGB/RGBA non-interlaced PNGs are read (bit depth ", depth,
                                     ", colour type ", colour, ")"));
            channels = colour == 2 ? 3 : 4;
        } else if (type == "IDAT") {
            packed += data;
        } else if (type == "IEND") {
            ended = true;
        }
        at += 12 + length;
    }
    if (channels == 0 || !ended) throw IoError(concat(what, ": PNG without ", channels == 0 ? "IHDR" : "IEND"));
    Canvas canvas(width, height); // throws InputError on absurd sizes
    const std::size_t stride = channels * width;
    std::vector<unsigned char> raw((stride + 1) * height);
    uLongf raw_size = static_cast<uLongf>(raw.size());
    if (uncompress(raw.data(), &raw_size, reinterpret_cast<const Bytef*>(packed.data()),
                   static_cast<uLong>(packed.size())) != Z_OK ||
        raw_size != raw.size())
        throw IoError(concat(what, ": PNG image data does not inflate to ", width, " x ", height, " pixels"));
    unfilter(raw, stride, height, channels, what);
    for (std::size_t y = 0; y < height; ++y)
        for (std::size_t x = 0; x < width; ++x) {
            const unsigned char* p = &raw[y * (stride + 1) + 1 + x * channels];
            canvas.set(static_cast<long>(x), static_cast<long>(y), {p[0], p[1], p[2]});
        }
    return canvas;
}

} // namespace tissuemesh::render

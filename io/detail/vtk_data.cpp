// Decoding VTK XML DataArrays (declared in vtk_xml.h).
#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <zlib.h>

#include "core/error.h"
#include "io/detail/vtk_xml.h"

namespace tissuemesh::io::detail {
namespace {

struct NumberType {
    std::size_t size = 0; ///< bytes; 0 for an unknown type
    char kind = 'f';      ///< 'i' signed integer, 'u' unsigned integer, 'f' floating point
};

NumberType number_type(const std::string& name)
{
    static const std::map<std::string, NumberType> types{
        {"Int8", {1, 'i'}},   {"UInt8", {1, 'u'}}, {"Int16", {2, 'i'}},  {"UInt16", {2, 'u'}},  {"Int32", {4, 'i'}},
        {"UInt32", {4, 'u'}}, {"Int64", {8, 'i'}}, {"UInt64", {8, 'u'}}, {"Float32", {4, 'f'}}, {"Float64", {8, 'f'}}};
    const auto found = types.find(name);
    return found == types.end() ? NumberType{} : found->second;
}

template <typename T>
double load(const char* at)
{
    T value;
    std::memcpy(&value, at, sizeof(T));
    return static_cast<double>(value);
}

double to_double(const char* at, NumberType type)
{
    switch (type.size * 4 + (type.kind == 'i' ? 0 : type.kind == 'u' ? 1 : 2)) {
    case 4: return load<std::int8_t>(at);
    case 5: return load<std::uint8_t>(at);
    case 8: return load<std::int16_t>(at);
    case 9: return load<std::uint16_t>(at);
    case 16: return load<std::int32_t>(at);
    case 17: return load<std::uint32_t>(at);
    case 18: return load<float>(at);
    case 32: return load<std::int64_t>(at);
    case 33: return load<std::uint64_t>(at);
    default: return load<double>(at);
    }
}

/// Reports problems with one array: "file: DataArray "name" problem (at byte N); fix".
struct ArrayContext {
    const VtkXmlFile& file;
    const VtkDataArray& array;
    [[noreturn]] void fail(const std::string& problem,
                           const std::string& fix = "the file is truncated or corrupt; write it again") const
    {
        throw IoError(
            concat(file.what, ": DataArray \"", array.name(), "\" ", problem, " (at byte ", array.at, "); ", fix));
    }
};

std::vector<double> parse_ascii(const ArrayContext& context, std::size_t values)
{
    const std::string_view text = context.array.text;
    std::vector<double> out;
    out.reserve(std::min(values, text.size() / 2 + 1)); // a number and a separator take 2 bytes at least
    const char* at = text.data();
    const char* end = text.data() + text.size();
    while (true) {
        while (at < end && std::isspace(static_cast<unsigned char>(*at))) ++at;
        if (at == end) break;
        double value = 0;
        const auto [stop, error] = std::from_chars(at, end, value);
        if (error != std::errc() || (stop < end && !std::isspace(static_cast<unsigned char>(*stop))))
            context.fail(concat("holds \"",
                                std::string_view(at, static_cast<std::size_t>(std::min<std::ptrdiff_t>(end - at, 20))),
                                "\", not a number"));
        if (out.size() == values) context.fail(concat("holds more than the ", values, " values the piece needs"));
        out.push_back(value);
        at = stop;
    }
    if (out.size() != values) context.fail(concat("holds ", out.size(), " values where ", values, " are needed"));
    return out;
}

/// The data bytes of a block sequence `data` (header words of `header_size` bytes, then the data or its zlib
/// blocks), which must hold exactly `needed` bytes.
std::string unpack_blocks(const ArrayContext& context, std::string_view data, bool compressed, std::size_t header_size,
                          std::size_t needed)
{
    const auto word = [&](std::size_t i) {
        if (data.size() / header_size <= i) context.fail("ends inside its header");
        if (header_size == 4)
            return static_cast<std::uint64_t>(static_cast<std::uint32_t>(load<std::uint32_t>(data.data() + 4 * i)));
        return static_cast<std::uint64_t>(load<std::uint64_t>(data.data() + 8 * i));
    };
    const auto mismatch = [&](std::uint64_t bytes) {
        context.fail(concat("holds ", bytes, " bytes where the piece needs ", needed));
    };
    if (!compressed) {
        const std::uint64_t bytes = word(0);
        if (bytes != needed) mismatch(bytes);
        if (bytes > data.size() - header_size)
            context.fail(concat("announces ", bytes, " bytes but only ", data.size() - header_size, " follow"));
        return std::string(data.substr(header_size, needed));
    }
    const std::uint64_t blocks = word(0), block = word(1), last = word(2);
    if (blocks > data.size() / header_size)
        context.fail(concat("announces ", blocks, " compressed blocks but only ", data.size(), " bytes follow"));
    const std::uint64_t last_size = last == 0 ? block : last;
    if (blocks > 0 && (last_size > block || blocks - 1 > needed / std::max<std::uint64_t>(block, 1)))
        mismatch(blocks * block);
    const std::uint64_t total = blocks == 0 ? 0 : (blocks - 1) * block + last_size;
    if (total != needed) mismatch(total);
    std::size_t at = static_cast<std::size_t>((3 + blocks) * header_size);
    if (at > data.size()) context.fail("ends inside its header");
    std::string out(needed, '\0');
    for (std::uint64_t b = 0; b < blocks; ++b) {
        const std::uint64_t packed = word(static_cast<std::size_t>(3 + b)), raw = b + 1 == blocks ? last_size : block;
        if (packed > data.size() - at)
            context.fail(
                concat("block ", b, " announces ", packed, " compressed bytes but only ", data.size() - at, " follow"));
        // A deflate stream expands at most 1032-fold: a larger claim is corrupt (and must not be allocated).
        if (raw > 1032 * packed + 64)
            context.fail(concat("block ", b, " claims ", raw, " bytes from ", packed, " compressed bytes"));
        auto length = static_cast<uLongf>(raw);
        const int status = uncompress(reinterpret_cast<Bytef*>(out.data() + b * block), &length,
                                      reinterpret_cast<const Bytef*>(data.data() + at), static_cast<uLong>(packed));
        if (status != Z_OK || length != raw) context.fail(concat("block ", b, " is not valid zlib data"));
        at += static_cast<std::size_t>(packed);
    }
    return out;
}

/// The encoded bytes of an appended array: raw from its offset on (a view of the file), base64 up to the next
/// array's offset (decoded into `decoded`).
std::string_view appended_bytes(const ArrayContext& context, std::size_t offset, std::string& decoded)
{
    const VtkXmlFile& file = context.file;
    if (file.appended_encoding.empty())
        context.fail("is appended but the file has no <AppendedData>", "the file is truncated");
    if (offset > file.appended.size())
        context.fail(concat("starts at offset ", offset, ", past the ", file.appended.size(), " appended bytes"));
    if (file.appended_encoding == "raw") return file.appended.substr(offset);
    std::size_t end = file.appended.size();
    for (const VtkDataArray& other : file.arrays) {
        std::size_t start = 0;
        const std::string text = other.attribute("offset");
        if (other.attribute("format") != "appended" ||
            std::from_chars(text.data(), text.data() + text.size(), start).ec != std::errc())
            continue;
        if (start > offset && start < end) end = start;
    }
    if (!decode_base64(file.appended.substr(offset, end - offset), decoded)) context.fail("is not valid base64");
    return decoded;
}

} // namespace

bool decode_base64(std::string_view text, std::string& out)
{
    out.reserve(out.size() + text.size() / 4 * 3 + 3);
    std::uint32_t bits = 0;
    int count = 0; // sextets in `bits`
    // The bytes of a partial group (2 or 3 sextets) at padding or at the end; a new stream may follow padding.
    const auto flush = [&] {
        if (count == 2) out += static_cast<char>((bits >> 4) & 0xff);
        if (count == 3) out += static_cast<char>((bits >> 10) & 0xff), out += static_cast<char>((bits >> 2) & 0xff);
        count = 0, bits = 0;
    };
    for (const char c : text) {
        int value = -1;
        if (c >= 'A' && c <= 'Z') value = c - 'A';
        else if (c >= 'a' && c <= 'z') value = c - 'a' + 26;
        else if (c >= '0' && c <= '9') value = c - '0' + 52;
        else if (c == '+') value = 62;
        else if (c == '/') value = 63;
        else if (c == '=') flush();
        else if (!std::isspace(static_cast<unsigned char>(c))) return false;
        if (value < 0) continue;
        bits = (bits << 6) | static_cast<std::uint32_t>(value);
        if (++count == 4) {
            for (const int shift : {16, 8, 0}) out += static_cast<char>((bits >> shift) & 0xff);
            count = 0, bits = 0;
        }
    }
    flush();
    return true;
}

std::vector<double> decode_data_array(const VtkXmlFile& file, const VtkDataArray& array, std::size_t values,
                                      const char* items)
{
    const ArrayContext context{file, array};
    const std::string type_name = array.attribute("type"), format = array.attribute("format");
    const NumberType type = number_type(type_name);
    if (type.size == 0)
        context.fail(concat("has type \"", type_name, "\""), "write Int8..UInt64, Float32 or Float64 arrays");
    if (format == "ascii" || (format.empty() && !array.text.empty())) return parse_ascii(context, values);
    if (format != "binary" && format != "appended")
        context.fail(concat("has format \"", format, "\""), "save the file with ascii, binary or appended data");
    if (values > (std::size_t{1} << 40) / type.size)
        context.fail(concat("would hold ", values, " ", items), "the file is corrupt");
    std::string decoded;
    std::string_view encoded;
    if (format == "binary") {
        if (!decode_base64(array.text, decoded)) context.fail("is not valid base64");
        encoded = decoded;
    } else {
        std::size_t offset = 0;
        const std::string text = array.attribute("offset");
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), offset);
        if (error != std::errc() || end != text.data() + text.size())
            context.fail(concat("has offset \"", text, "\""), "the file is corrupt");
        encoded = appended_bytes(context, offset, decoded);
    }
    const std::string header = file.vtk_file.count("header_type") ? file.vtk_file.at("header_type") : "UInt32";
    const std::string bytes = unpack_blocks(context, encoded, file.vtk_file.count("compressor") > 0,
                                            header == "UInt64" ? 8 : 4, values * type.size);
    std::vector<double> out(values);
    for (std::size_t i = 0; i < values; ++i) out[i] = to_double(bytes.data() + i * type.size, type);
    return out;
}

} // namespace tissuemesh::io::detail

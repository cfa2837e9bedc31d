#include "io/detail/text_header.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <zlib.h>

#include "core/atomic_file.h"
#include "core/error.h"

namespace tissuemesh::io::detail {
namespace fs = std::filesystem;

namespace {

/// The largest expansion of a deflate (gzip, zlib) stream: 1032 output bytes per input byte.
constexpr std::uint64_t deflate_ratio = 1032;

struct TextHeader {
    std::map<std::string, std::string> fields; ///< lower-case keys without spaces
    std::uint64_t header_bytes = 0;            ///< where attached data starts
};

std::string trim(const std::string& text)
{
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos) return {};
    return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

std::string normal_key(std::string key)
{
    key.erase(std::remove(key.begin(), key.end(), ' '), key.end());
    std::transform(key.begin(), key.end(), key.begin(), [](unsigned char c) { return std::tolower(c); });
    return key;
}

/// NRRD: "NRRD000N" then "key: value" lines up to an empty line (attached data follows it).
/// MetaImage: "Key = Value" lines, the last of which is ElementDataFile.
TextHeader parse_header(const fs::path& path, bool nrrd)
{
    std::ifstream in(path, std::ios::binary);
    TextHeader header;
    std::string line;
    bool first = true;
    // Headers are small; a line longer than this is binary data, not header.
    constexpr std::size_t max_line = 1 << 16;
    for (int line_number = 1; std::getline(in, line) && line.size() < max_line; ++line_number) {
        header.header_bytes += line.size() + 1;
        if (first && nrrd && !line.starts_with("NRRD"))
            throw IoError(concat(path.string(), ": not a NRRD file (wrong magic, it does not start with "
                                                "\"NRRD\"); check that the file is not renamed or damaged"));
        first = false;
        const std::string text = trim(line);
        if (nrrd && text.empty()) break;
        if (text.empty() || text[0] == '#') continue;
        const auto colon = text.find(nrrd ? ":" : "=");
        // MetaIO would read such a key's value from the next line ("ElementDataFile\nOffset = a %n 0 1 2"
        // becomes a file pattern it loops over forever): a MetaImage header has "Key = Value" lines only.
        if (colon == std::string::npos && !nrrd && header.fields.empty())
            throw IoError(concat(path.string(), ": not a MetaImage file (wrong magic: its first line is not "
                                                "\"Key = Value\"); check that the file is not renamed or damaged"));
        if (colon == std::string::npos && !nrrd)
            throw IoError(concat(path.string(), ": header line ", line_number, " (\"", text.substr(0, 40),
                                 "\") is not \"Key = Value\"; the header is damaged. Export the image again"));
        if (colon == std::string::npos || (nrrd && text.compare(colon, 2, ":=") == 0)) continue;
        const std::string written_key = trim(text.substr(0, colon));
        // MetaIO copies a key into a 255-byte field name unchecked (a longer one overruns it); real keys
        // are single words like "ElementSpacing".
        constexpr std::size_t max_key = 64;
        if (!nrrd && written_key.empty())
            throw IoError(concat(path.string(), ": header line ", line_number,
                                 " has no key before its '='; the header is damaged. Export the image again"));
        // MetaIO matches keys as written: "ElementDat aFile" is no ElementDataFile to it, so a later line could
        // name its data file (a '%' pattern it overran a buffer on) while this check read the first one.
        if (!nrrd && written_key.find_first_of(" \t") != std::string::npos)
            throw IoError(concat(path.string(), ": header line ", line_number, " has a key with a space in it ('",
                                 written_key.substr(0, 40), "'); the header is damaged. Export the image again"));
        if (!nrrd && written_key.size() > max_key)
            throw IoError(concat(path.string(), ": header line ", line_number, " has a key of ", written_key.size(),
                                 " characters (at most ", max_key,
                                 " in a MetaImage header); the header is damaged. Export the image again"));
        const std::string key = normal_key(text.substr(0, colon));
        // Our checks read one value per key; MetaIO acts on every repeat in turn ("NDims = 444...3" then
        // "NDims = 3" passed our check and had MetaIO read billions of numbers): a key may come once.
        if (!nrrd && header.fields.count(key))
            throw IoError(concat(path.string(), ": header line ", line_number, " repeats the key '", written_key,
                                 "'; the header is damaged. Export the image again"));
        header.fields[key] = trim(text.substr(colon + 1));
        if (!nrrd && key == "elementdatafile") break;
    }
    return header;
}

std::uint64_t data_file_size(const fs::path& header_path, const std::string& data_file)
{
    if (data_file == "LIST" || data_file.starts_with("LIST ") || data_file.find('%') != std::string::npos ||
        data_file.find(' ') != std::string::npos)
        throw IoError(concat(header_path.string(), ": voxel data split over several files ('", data_file,
                             "') is not supported; save the volume as one file"));
    const fs::path data = header_path.parent_path() / data_file;
    std::error_code ec;
    if (!fs::is_regular_file(data, ec))
        throw IoError(concat(header_path.string(), ": its data file ", data.string(),
                             " does not exist; keep the header and its data file together"));
    return fs::file_size(data, ec);
}

/// Whether `bytes` bytes of `file` from `offset` hold one whole zlib stream: inflated through a small
/// scratch buffer (nothing kept). MetaIO's own inflate loop never ends on a stream that asks for a preset
/// dictionary or breaks off, so the stream is proven whole before MetaIO sees it.
bool whole_zlib_stream(const fs::path& file, std::uint64_t offset, std::uint64_t bytes)
{
    std::ifstream in(file, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(offset));
    z_stream stream{};
    if (inflateInit(&stream) != Z_OK) return false;
    std::vector<unsigned char> input(1 << 16), output(1 << 16);
    int status = Z_OK;
    while (status == Z_OK && bytes > 0 && in) {
        in.read(reinterpret_cast<char*>(input.data()),
                static_cast<std::streamsize>(std::min<std::uint64_t>(bytes, input.size())));
        const auto got = static_cast<std::uint64_t>(in.gcount());
        if (got == 0) break;
        bytes -= got;
        stream.next_in = input.data();
        stream.avail_in = static_cast<uInt>(got);
        do {
            stream.next_out = output.data();
            stream.avail_out = static_cast<uInt>(output.size());
            status = inflate(&stream, Z_NO_FLUSH);
        } while (status == Z_OK && stream.avail_in > 0);
    }
    inflateEnd(&stream);
    return status == Z_STREAM_END;
}

std::uint64_t nrrd_bound(const fs::path& path)
{
    const TextHeader header = parse_header(path, true);
    std::uint64_t stored = 0;
    const auto data_file = header.fields.count("datafile") ? header.fields.at("datafile") : std::string();
    if (!data_file.empty()) {
        stored = data_file_size(path, data_file);
    } else {
        const auto size = fs::file_size(path);
        stored = size > header.header_bytes ? size - header.header_bytes : 0;
    }
    const std::string encoding = header.fields.count("encoding") ? header.fields.at("encoding") : "raw";
    if (encoding == "raw") return stored;
    if (encoding == "hex") return stored / 2;
    // Text voxels take at least two characters ("0 ") for up to eight bytes.
    if (encoding == "ascii" || encoding == "text" || encoding == "txt") return stored * 4;
    return stored * deflate_ratio;
}

std::uint64_t meta_image_bound(const fs::path& path)
{
    const TextHeader header = parse_header(path, false);
    if (!header.fields.count("elementdatafile") || !header.fields.count("dimsize"))
        throw IoError(concat(path.string(), ": not a MetaImage file (wrong magic: no DimSize or "
                                            "ElementDataFile line); check that the file is not renamed or damaged"));
    // MetaIO reads NDims values per field with an unsigned count: "NDims = -1" has it reading 2^32 numbers.
    const auto ndims = header.fields.find("ndims");
    if (ndims != header.fields.end()) {
        char* end = nullptr;
        const long dimensions = std::strtol(ndims->second.c_str(), &end, 10);
        if (end == ndims->second.c_str() || *end != '\0' || dimensions < 1 || dimensions > 4)
            throw IoError(concat(path.string(), ": NDims is '", ndims->second.substr(0, 20),
                                 "', not a dimension count of 1 to 4; the header is damaged. Export the image again"));
    }
    const std::string data_file = header.fields.at("elementdatafile");
    std::uint64_t stored = 0;
    const bool local = data_file == "LOCAL";
    if (local) {
        const auto size = fs::file_size(path);
        stored = size > header.header_bytes ? size - header.header_bytes : 0;
    } else {
        stored = data_file_size(path, data_file);
    }
    const auto compressed = header.fields.find("compresseddata");
    if (compressed == header.fields.end() || normal_key(compressed->second) != "true") return stored;
    // MetaIO does not notice a short compressed stream; the header says how long it must be.
    const auto compressed_size = header.fields.find("compresseddatasize");
    if (compressed_size != header.fields.end()) {
        const std::uint64_t expected = std::strtoull(compressed_size->second.c_str(), nullptr, 10);
        if (expected > stored)
            throw IoError(concat(path.string(), ": truncated, the header announces ", expected,
                                 " bytes of compressed voxel data but the file holds ", stored,
                                 "; the file is incomplete. Copy or export it again"));
        stored = expected;
    }
    if (!whole_zlib_stream(local ? path : path.parent_path() / data_file, local ? header.header_bytes : 0, stored))
        throw IoError(concat(path.string(),
                             ": its compressed voxel data is not one whole zlib stream (broken off, "
                             "damaged or needing a preset dictionary); the file is damaged. Export the image again"));
    return stored * deflate_ratio;
}

} // namespace

std::uint64_t text_header_payload_bound(const fs::path& path)
{
    const std::string extension = full_extension(path);
    if (extension == ".mha" || extension == ".mhd") return meta_image_bound(path);
    return nrrd_bound(path);
}

} // namespace tissuemesh::io::detail

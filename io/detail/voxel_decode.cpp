#include "io/detail/voxel_decode.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <type_traits>

#include <zlib.h>

#include "core/error.h"

namespace tissuemesh::io::detail {
namespace fs = std::filesystem;

namespace {

struct TypeInfo {
    VoxelType type;
    const char* name;
    std::size_t size;
};

constexpr std::array<TypeInfo, 10> type_table{{
    {VoxelType::u8, "uint8", 1},
    {VoxelType::i8, "int8", 1},
    {VoxelType::u16, "uint16", 2},
    {VoxelType::i16, "int16", 2},
    {VoxelType::u32, "uint32", 4},
    {VoxelType::i32, "int32", 4},
    {VoxelType::u64, "uint64", 8},
    {VoxelType::i64, "int64", 8},
    {VoxelType::f32, "float32", 4},
    {VoxelType::f64, "float64", 8},
}};

const TypeInfo& info(VoxelType type)
{
    for (const TypeInfo& entry : type_table)
        if (entry.type == type) return entry;
    return type_table[0];
}

std::string voxel_text(const Dims& dims, std::size_t linear)
{
    const std::size_t i = linear % dims[0];
    const std::size_t j = linear / dims[0] % dims[1];
    const std::size_t k = linear / dims[0] / dims[1];
    return concat("voxel (", i, ", ", j, ", ", k, ")");
}

template <typename T>
T load(const unsigned char* bytes, std::size_t linear, bool swap)
{
    std::array<unsigned char, sizeof(T)> buffer;
    std::memcpy(buffer.data(), bytes + linear * sizeof(T), sizeof(T));
    if (swap)
        for (std::size_t b = 0; b < sizeof(T) / 2; ++b) std::swap(buffer[b], buffer[sizeof(T) - 1 - b]);
    T value;
    std::memcpy(&value, buffer.data(), sizeof(T));
    return value;
}

[[noreturn]] void reject_value(const std::string& file, const Dims& dims, std::size_t linear,
                               const std::string& value_text, bool fractional)
{
    if (fractional)
        throw InputError(concat(file, ": ", voxel_text(dims, linear), " holds ", value_text,
                                "; labels must be whole numbers. The image looks like intensities or "
                                "probabilities: threshold or round it into an integer label map"));
    throw InputError(concat(file, ": ", voxel_text(dims, linear), " holds ", value_text,
                            "; labels must lie in 0..65535. Renumber the tissues into that range"));
}

template <typename T>
void decode(const std::string& file, const unsigned char* bytes, bool swap, const Dims& dims,
            std::vector<Label>& labels)
{
    for (std::size_t n = 0; n < labels.size(); ++n) {
        const T value = load<T>(bytes, n, swap);
        if constexpr (std::is_floating_point_v<T>) {
            if (!std::isfinite(value) || value != std::floor(value))
                reject_value(file, dims, n, concat(static_cast<double>(value)), true);
            if (value < 0 || value > 65535) reject_value(file, dims, n, concat(static_cast<double>(value)), false);
        } else {
            if constexpr (std::is_signed_v<T>) {
                if (value < 0) reject_value(file, dims, n, std::to_string(value), false);
            }
            if (static_cast<std::uint64_t>(value) > 65535) reject_value(file, dims, n, std::to_string(value), false);
        }
        labels[n] = static_cast<Label>(value);
    }
}

bool host_is_big_endian()
{
    const std::uint16_t probe = 1;
    unsigned char first;
    std::memcpy(&first, &probe, 1);
    return first == 0;
}

template <typename T>
void rescale(const unsigned char* bytes, bool swap, std::size_t count, double slope, double intercept,
             std::vector<unsigned char>& out)
{
    for (std::size_t n = 0; n < count; ++n) {
        const double value = slope * static_cast<double>(load<T>(bytes, n, swap)) + intercept;
        std::memcpy(out.data() + 8 * n, &value, 8);
    }
}

} // namespace

std::vector<unsigned char> rescale_to_float64(const unsigned char* bytes, VoxelType type, bool big_endian,
                                              std::size_t count, double slope, double intercept)
{
    std::vector<unsigned char> out(count * 8);
    const bool swap = big_endian != host_is_big_endian();
    switch (type) {
    case VoxelType::u8: rescale<std::uint8_t>(bytes, swap, count, slope, intercept, out); break;
    case VoxelType::i8: rescale<std::int8_t>(bytes, swap, count, slope, intercept, out); break;
    case VoxelType::u16: rescale<std::uint16_t>(bytes, swap, count, slope, intercept, out); break;
    case VoxelType::i16: rescale<std::int16_t>(bytes, swap, count, slope, intercept, out); break;
    case VoxelType::u32: rescale<std::uint32_t>(bytes, swap, count, slope, intercept, out); break;
    case VoxelType::i32: rescale<std::int32_t>(bytes, swap, count, slope, intercept, out); break;
    case VoxelType::u64: rescale<std::uint64_t>(bytes, swap, count, slope, intercept, out); break;
    case VoxelType::i64: rescale<std::int64_t>(bytes, swap, count, slope, intercept, out); break;
    case VoxelType::f32: rescale<float>(bytes, swap, count, slope, intercept, out); break;
    case VoxelType::f64: rescale<double>(bytes, swap, count, slope, intercept, out); break;
    }
    return out;
}

std::size_t voxel_type_size(VoxelType type) { return info(type).size; }

std::string voxel_type_name(VoxelType type) { return info(type).name; }

std::optional<VoxelType> parse_voxel_type(const std::string& name)
{
    for (const TypeInfo& entry : type_table)
        if (name == entry.name) return entry.type;
    return std::nullopt;
}

std::uint64_t checked_voxel_bytes(const std::string& file, const Dims& dims, std::size_t bytes_per_voxel)
{
    std::uint64_t total = bytes_per_voxel;
    for (int axis = 0; axis < 3; ++axis) {
        if (dims[axis] == 0)
            throw InputError(concat(file, ": dimension ", axis,
                                    " is 0; an image needs at least one voxel "
                                    "along every axis. The header is corrupt"));
        if (total > std::numeric_limits<std::uint64_t>::max() / dims[axis])
            throw InputError(concat(file, ": dimensions ", dims[0], " x ", dims[1], " x ", dims[2],
                                    " overflow the voxel count; the header is corrupt"));
        total *= dims[axis];
    }
    return total;
}

void require_payload(const std::string& file, std::uint64_t needed_bytes, std::uint64_t available_bytes)
{
    if (needed_bytes > available_bytes)
        throw IoError(concat(file, ": truncated, the header's dimensions need ", needed_bytes,
                             " bytes of voxel data but the file holds ", available_bytes,
                             "; the file is incomplete or its header is corrupt. Copy or export it again"));
}

bool is_gzip_file(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    unsigned char magic[2] = {0, 0};
    in.read(reinterpret_cast<char*>(magic), 2);
    return in.gcount() == 2 && magic[0] == 0x1f && magic[1] == 0x8b;
}

std::uint64_t uncompressed_size(const fs::path& path)
{
    std::error_code ec;
    if (!is_gzip_file(path)) {
        const auto size = fs::file_size(path, ec);
        if (ec) throw IoError(concat(path.string(), ": cannot read (", ec.message(), "); check the path"));
        return size;
    }
    gzFile file = gzopen(path.c_str(), "rb");
    if (file == nullptr) throw IoError(concat(path.string(), ": cannot be opened; check the permissions"));
    std::vector<char> buffer(1 << 20);
    std::uint64_t total = 0;
    for (;;) {
        const int got = gzread(file, buffer.data(), static_cast<unsigned>(buffer.size()));
        if (got < 0) {
            int code = 0;
            const std::string reason = gzerror(file, &code);
            gzclose(file);
            throw IoError(concat(path.string(), ": corrupt gzip data (", reason,
                                 "); the file is damaged, copy or export it again"));
        }
        if (got == 0) break;
        total += static_cast<std::uint64_t>(got);
    }
    gzclose(file);
    return total;
}

std::vector<unsigned char> read_payload(const fs::path& path, std::uint64_t offset, std::uint64_t bytes)
{
    // gzread also reads uncompressed files (transparently), so one path serves .inr and .inr.gz.
    gzFile file = gzopen(path.c_str(), "rb");
    if (file == nullptr) throw IoError(concat(path.string(), ": cannot be opened; check the permissions"));
    std::vector<unsigned char> data(static_cast<std::size_t>(bytes));
    bool ok = gzseek(file, static_cast<z_off_t>(offset), SEEK_SET) == static_cast<z_off_t>(offset);
    std::size_t done = 0;
    while (ok && done < data.size()) {
        const std::size_t chunk = std::min<std::size_t>(data.size() - done, 1 << 30);
        const int got = gzread(file, data.data() + done, static_cast<unsigned>(chunk));
        ok = got > 0;
        if (ok) done += static_cast<std::size_t>(got);
    }
    gzclose(file);
    if (!ok)
        throw IoError(concat(path.string(), ": truncated or corrupt voxel data (read ", done, " of ", bytes,
                             " bytes); copy or export the file again"));
    return data;
}

std::size_t label_width(const LabelImage& image)
{
    const auto& labels = image.labels();
    return labels.empty() || *std::max_element(labels.begin(), labels.end()) <= 255 ? 1 : 2;
}

std::string encode_labels(const LabelImage& image, std::size_t width)
{
    std::string data(image.voxel_count() * width, '\0');
    for (std::size_t n = 0; n < image.voxel_count(); ++n) {
        const Label label = image.labels()[n];
        data[width * n] = static_cast<char>(label & 0xff);
        if (width == 2) data[2 * n + 1] = static_cast<char>(label >> 8);
    }
    return data;
}

void decode_labels(const std::string& file, const unsigned char* bytes, VoxelType type, bool big_endian,
                   LabelImage& image)
{
    std::vector<Label>& labels = image.labels();
    const Dims& dims = image.dims();
    const bool swap = big_endian != host_is_big_endian();
    switch (type) {
    case VoxelType::u8: decode<std::uint8_t>(file, bytes, swap, dims, labels); break;
    case VoxelType::i8: decode<std::int8_t>(file, bytes, swap, dims, labels); break;
    case VoxelType::u16: decode<std::uint16_t>(file, bytes, swap, dims, labels); break;
    case VoxelType::i16: decode<std::int16_t>(file, bytes, swap, dims, labels); break;
    case VoxelType::u32: decode<std::uint32_t>(file, bytes, swap, dims, labels); break;
    case VoxelType::i32: decode<std::int32_t>(file, bytes, swap, dims, labels); break;
    case VoxelType::u64: decode<std::uint64_t>(file, bytes, swap, dims, labels); break;
    case VoxelType::i64: decode<std::int64_t>(file, bytes, swap, dims, labels); break;
    case VoxelType::f32: decode<float>(file, bytes, swap, dims, labels); break;
    case VoxelType::f64: decode<double>(file, bytes, swap, dims, labels); break;
    }
}

std::vector<float> to_finite_floats(const std::string& file, const unsigned char* bytes, VoxelType type,
                                    bool big_endian, const LabelImage& grid)
{
    const std::size_t count = grid.voxel_count();
    const std::vector<unsigned char> doubles = rescale_to_float64(bytes, type, big_endian, count, 1, 0);
    std::vector<float> values(count);
    for (std::size_t v = 0; v < count; ++v) {
        double value = 0;
        std::memcpy(&value, doubles.data() + 8 * v, sizeof value);
        if (!std::isfinite(value)) {
            const Dims& d = grid.dims();
            throw InputError(concat(file, ": voxel (", v % d[0], ", ", (v / d[0]) % d[1], ", ", v / (d[0] * d[1]),
                                    ") holds ", value, "; grey values must be finite numbers"));
        }
        values[v] = static_cast<float>(value);
    }
    return values;
}

} // namespace tissuemesh::io::detail

#include "io/detail/inrimage.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <vector>

#include <zlib.h>

#include "core/error.h"
#include "io/detail/voxel_decode.h"

namespace tissuemesh::io::detail {
namespace fs = std::filesystem;

namespace {

constexpr std::size_t block_size = 256;
constexpr std::size_t max_header_blocks = 256; // 64 KiB: real headers use one block
const std::string magic = "#INRIMAGE-4#{";
const std::string header_end = "##}";

struct InrHeader {
    std::map<std::string, std::string> fields;
    std::size_t bytes = 0; ///< header size, a multiple of 256
};

InrHeader read_header(const fs::path& path)
{
    const std::string name = path.string();
    gzFile file = gzopen(path.c_str(), "rb");
    if (file == nullptr) throw IoError(concat(name, ": cannot be opened; check the permissions"));
    std::string text;
    std::vector<char> block(block_size);
    while (text.find(header_end) == std::string::npos && text.size() < max_header_blocks * block_size) {
        const int got = gzread(file, block.data(), static_cast<unsigned>(block_size));
        if (got <= 0) break;
        text.append(block.data(), static_cast<std::size_t>(got));
        if (!text.starts_with(magic.substr(0, std::min(text.size(), magic.size())))) break;
    }
    gzclose(file);
    if (!text.starts_with(magic))
        throw IoError(concat(name, ": not an Inrimage file (wrong magic: it does not start with \"", magic,
                             "\"); check that the file is not renamed or damaged"));
    const auto end = text.find(header_end);
    if (end == std::string::npos)
        throw IoError(concat(name, ": truncated Inrimage header (no \"##}\" line); the file is incomplete"));
    InrHeader header;
    header.bytes = (end / block_size + 1) * block_size;
    std::istringstream lines(text.substr(magic.size(), end - magic.size()));
    std::string line;
    while (std::getline(lines, line)) {
        const auto equals = line.find('=');
        if (line.empty() || line[0] == '#' || equals == std::string::npos) continue;
        header.fields[line.substr(0, equals)] = line.substr(equals + 1);
    }
    return header;
}

double number_field(const std::string& name, const InrHeader& header, const std::string& key, double fallback)
{
    const auto found = header.fields.find(key);
    if (found == header.fields.end()) return fallback;
    // strtod, unlike a stream, reads "nan" and "inf": validate_geometry() then names them.
    char* end = nullptr;
    const double value = std::strtod(found->second.c_str(), &end);
    if (end == found->second.c_str())
        throw IoError(concat(name, ": Inrimage header field ", key, "=", found->second,
                             " is not a number; the header is corrupt"));
    return value;
}

std::size_t dimension_field(const std::string& name, const InrHeader& header, const std::string& key, int axis)
{
    const double value = number_field(name, header, key, key == "ZDIM" ? 1 : -1);
    if (!(value >= 1) || value != std::floor(value) || value > 1e15)
        throw InputError(concat(name, ": dimension ", axis, " is ", value, " (", key,
                                "); every axis needs a "
                                "whole number of voxels, at least 1. The header is corrupt"));
    return static_cast<std::size_t>(value);
}

VoxelType voxel_type(const std::string& name, const InrHeader& header)
{
    const auto type = header.fields.count("TYPE") ? header.fields.at("TYPE") : "unsigned fixed";
    const double bits = number_field(name, header, "PIXSIZE", 8);
    const bool is_float = type == "float";
    const bool is_signed = type == "signed fixed";
    if (!is_float && !is_signed && type != "unsigned fixed")
        throw IoError(
            concat(name, ": unsupported Inrimage TYPE=", type, "; expected unsigned fixed, signed fixed or float"));
    if (is_float && bits == 32) return VoxelType::f32;
    if (is_float && bits == 64) return VoxelType::f64;
    if (!is_float && bits == 8) return is_signed ? VoxelType::i8 : VoxelType::u8;
    if (!is_float && bits == 16) return is_signed ? VoxelType::i16 : VoxelType::u16;
    if (!is_float && bits == 32) return is_signed ? VoxelType::i32 : VoxelType::u32;
    if (!is_float && bits == 64) return is_signed ? VoxelType::i64 : VoxelType::u64;
    throw IoError(concat(name, ": unsupported Inrimage PIXSIZE=", bits, " bits for TYPE=", type,
                         "; expected 8, 16, 32 or 64 bits"));
}

bool big_endian_cpu(const std::string& name, const InrHeader& header)
{
    const auto found = header.fields.find("CPU");
    if (found == header.fields.end()) return false;
    const std::string& cpu = found->second;
    if (cpu == "decm" || cpu == "alpha" || cpu == "pc") return false;
    if (cpu == "sun" || cpu == "sgi") return true;
    throw IoError(concat(name, ": unknown Inrimage CPU=", cpu, "; expected decm, alpha, pc, sun or sgi"));
}

} // namespace

InrimageLayout read_inrimage_layout(const fs::path& path)
{
    const std::string name = path.string();
    const InrHeader header = read_header(path);
    InrimageLayout layout;
    layout.dims = {dimension_field(name, header, "XDIM", 0), dimension_field(name, header, "YDIM", 1),
                   dimension_field(name, header, "ZDIM", 2)};
    const double values = number_field(name, header, "VDIM", 1);
    if (values != 1)
        throw InputError(concat(name, ": ", values,
                                " values per voxel (VDIM); a label map holds one value per "
                                "voxel. Extract one component"));
    layout.type = voxel_type(name, header);
    layout.big_endian = big_endian_cpu(name, header);
    layout.spacing_mm = {number_field(name, header, "VX", 1), number_field(name, header, "VY", 1),
                         number_field(name, header, "VZ", 1)};
    layout.origin_mm = {number_field(name, header, "TX", number_field(name, header, "XO", 0)),
                        number_field(name, header, "TY", number_field(name, header, "YO", 0)),
                        number_field(name, header, "TZ", number_field(name, header, "ZO", 0))};
    layout.header_bytes = header.bytes;
    validate_geometry(name, layout.dims, layout.spacing_mm, identity_matrix());
    return layout;
}

LabelImage read_inrimage(const fs::path& path, const BeforeVoxels& before_voxels)
{
    const std::string name = path.string();
    const InrimageLayout layout = read_inrimage_layout(path);
    const std::uint64_t needed = checked_voxel_bytes(name, layout.dims, voxel_type_size(layout.type));
    const std::uint64_t size = uncompressed_size(path);
    require_payload(name, needed, size > layout.header_bytes ? size - layout.header_bytes : 0);
    if (before_voxels) before_voxels(layout.dims, layout.spacing_mm, voxel_type_size(layout.type));
    const std::vector<unsigned char> bytes = read_payload(path, layout.header_bytes, needed);
    LabelImage image(layout.dims, layout.spacing_mm, layout.origin_mm);
    decode_labels(name, bytes.data(), layout.type, layout.big_endian, image);
    return image;
}

void write_inrimage(const LabelImage& image, const fs::path& path, const std::string& name, bool compress)
{
    for (int n = 0; n < 9; ++n)
        if (std::abs(image.direction()[n] - identity_matrix()[n]) > 1e-9)
            throw InputError(concat(name, ": Inrimage cannot store the image's orientation (its direction "
                                          "matrix is not the identity); write .nii.gz, .nrrd or .mha instead"));
    const std::size_t width = label_width(image);
    std::ostringstream text;
    text.precision(17);
    text << magic << "\nXDIM=" << image.dims()[0] << "\nYDIM=" << image.dims()[1] << "\nZDIM=" << image.dims()[2]
         << "\nVDIM=1\nTYPE=unsigned fixed\nPIXSIZE=" << 8 * width
         << " bits\nSCALE=2**0\nCPU=decm\nVX=" << image.spacing_mm()[0] << "\nVY=" << image.spacing_mm()[1]
         << "\nVZ=" << image.spacing_mm()[2] << "\n";
    const Vec3& origin = image.origin_mm();
    if (origin[0] != 0 || origin[1] != 0 || origin[2] != 0)
        text << "TX=" << origin[0] << "\nTY=" << origin[1] << "\nTZ=" << origin[2] << "\n";
    std::string header = text.str();
    const std::size_t used = header.size() + header_end.size() + 1;
    header.append((used + block_size - 1) / block_size * block_size - used, '\n');
    header += header_end + "\n";

    const std::string data = encode_labels(image, width);
    gzFile file = gzopen(path.c_str(), compress ? "wb6" : "wbT");
    bool ok = file != nullptr;
    if (ok) ok = gzwrite(file, header.data(), static_cast<unsigned>(header.size())) == static_cast<int>(header.size());
    for (std::size_t done = 0; ok && done < data.size();) {
        const std::size_t chunk = std::min<std::size_t>(data.size() - done, 1 << 30);
        ok = gzwrite(file, data.data() + done, static_cast<unsigned>(chunk)) == static_cast<int>(chunk);
        done += chunk;
    }
    if (file != nullptr && gzclose(file) != Z_OK) ok = false;
    if (!ok) throw IoError(concat(name, ": cannot write (disk full or no permission); check the folder"));
}

} // namespace tissuemesh::io::detail

#include "io/detail/raw_json_image.h"

#include <algorithm>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/detail/tissue_names.h"
#include "io/detail/voxel_decode.h"

namespace tissuemesh::io::detail {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const json& required(const std::string& name, const json& document, const std::string& key)
{
    if (!document.contains(key))
        throw InputError(concat(name, ": the key \"", key,
                                "\" is missing; see the raw + JSON schema in "
                                "io/detail/raw_json_image.h"));
    return document[key];
}

Vec3 vec3(const std::string& name, const json& value, const std::string& key)
{
    if (!value.is_array() || value.size() != 3 ||
        !std::all_of(value.begin(), value.end(), [](const json& v) { return v.is_number(); }))
        throw InputError(concat(name, ": \"", key, "\" must be an array of 3 numbers, found ", value.dump()));
    return {value[0].get<double>(), value[1].get<double>(), value[2].get<double>()};
}

Dims dims_of(const std::string& name, const json& value)
{
    if (!value.is_array() || value.size() != 3)
        throw InputError(concat(name, ": \"dims\" must be an array of 3 positive integers, found ", value.dump()));
    Dims dims{};
    for (std::size_t axis = 0; axis < 3; ++axis) {
        if (!value[axis].is_number_integer() || value[axis].get<std::int64_t>() <= 0)
            throw InputError(concat(name, ": dimension ", axis, " is ", value[axis].dump(),
                                    "; \"dims\" must hold 3 positive integers"));
        dims[axis] = value[axis].get<std::size_t>();
    }
    return dims;
}

Mat3 direction_of(const std::string& name, const json& document)
{
    if (!document.contains("direction")) return identity_matrix();
    const json& rows = document["direction"];
    if (!rows.is_array() || rows.size() != 3)
        throw InputError(concat(name, ": \"direction\" must be 3 rows of 3 numbers, found ", rows.dump()));
    Mat3 direction{};
    for (std::size_t row = 0; row < 3; ++row) {
        const Vec3 values = vec3(name, rows[row], "direction");
        for (std::size_t column = 0; column < 3; ++column) direction[3 * row + column] = values[column];
    }
    return direction;
}

} // namespace

LabelImage read_raw_json_image(const fs::path& path, const BeforeVoxels& before_voxels)
{
    const std::string name = path.string();
    std::ifstream in(path, std::ios::binary);
    const json document = json::parse(in, nullptr, false);
    if (document.is_discarded() || !document.is_object())
        throw IoError(concat(name, ": not a valid JSON object; check the syntax (quotes, commas, braces)"));
    const Dims dims = dims_of(name, required(name, document, "dims"));
    const Vec3 spacing = vec3(name, required(name, document, "spacing"), "spacing");
    const Vec3 origin = document.contains("origin") ? vec3(name, document["origin"], "origin") : Vec3{0, 0, 0};
    const Mat3 direction = direction_of(name, document);
    const json& dtype = required(name, document, "dtype");
    const auto type = dtype.is_string() ? parse_voxel_type(dtype.get<std::string>()) : std::nullopt;
    if (!type)
        throw InputError(concat(name, ": unknown dtype ", dtype.dump(),
                                "; use uint8, int8, uint16, int16, "
                                "uint32, int32, float32 or float64"));
    const std::string byte_order = document.value("byte_order", std::string("little"));
    if (byte_order != "little" && byte_order != "big")
        throw InputError(concat(name, ": byte_order \"", byte_order, "\" must be \"little\" or \"big\""));
    const json& raw_name = required(name, document, "raw_file");
    if (!raw_name.is_string() || raw_name.get<std::string>().empty())
        throw InputError(concat(name, ": \"raw_file\" must be a file name relative to the JSON's folder"));
    const fs::path raw = path.parent_path() / raw_name.get<std::string>();
    std::error_code ec;
    if (!fs::is_regular_file(raw, ec))
        throw IoError(concat(name, ": its raw file ", raw.string(),
                             " does not exist; keep the .json and its "
                             "raw file together"));

    validate_geometry(name, dims, spacing, direction);
    const std::uint64_t needed = checked_voxel_bytes(name, dims, voxel_type_size(*type));
    require_payload(raw.string(), needed, uncompressed_size(raw));
    if (before_voxels) before_voxels(dims, spacing, voxel_type_size(*type));
    const std::vector<unsigned char> bytes = read_payload(raw, 0, needed);
    LabelImage image(dims, spacing, origin, direction);
    decode_labels(raw.string(), bytes.data(), *type, byte_order == "big", image);
    if (document.contains("labels")) image.names() = parse_tissue_names(name, document["labels"]);
    return image;
}

void write_raw_json_image(const LabelImage& image, const fs::path& path)
{
    const std::size_t width = label_width(image);
    const fs::path raw = fs::path(path).replace_extension(".raw");
    json document = json::object();
    document["dims"] = image.dims();
    document["spacing"] = image.spacing_mm();
    document["origin"] = image.origin_mm();
    const Mat3& d = image.direction();
    document["direction"] = {{d[0], d[1], d[2]}, {d[3], d[4], d[5]}, {d[6], d[7], d[8]}};
    document["dtype"] = width == 1 ? "uint8" : "uint16";
    document["byte_order"] = "little";
    document["order"] = "x-fastest (index = x + nx*(y + ny*z))";
    document["raw_file"] = raw.filename().string();
    json labels = json::object();
    for (const auto& [label, tissue] : image.names()) labels[std::to_string(label)] = tissue;
    document["labels"] = labels;
    // The raw file first: the sidecar never names data that is not there yet.
    write_text_atomically(raw, encode_labels(image, width));
    write_text_atomically(path, document.dump(1) + "\n");
}

} // namespace tissuemesh::io::detail

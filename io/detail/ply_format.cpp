#include "io/detail/ply_format.h"

#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "io/detail/chunked_output.h"

namespace tissuemesh::io::detail {
namespace {

template <typename T>
void append(std::string& out, T value)
{
    static_assert(std::endian::native == std::endian::little, "PLY writer assumes a little-endian host");
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    out.append(bytes, sizeof(T));
}

enum class Scalar { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

bool scalar_from_name(const std::string& name, Scalar& scalar)
{
    static const std::pair<const char*, Scalar> names[] = {
        {"char", Scalar::int8},      {"int8", Scalar::int8},       {"uchar", Scalar::uint8},
        {"uint8", Scalar::uint8},    {"short", Scalar::int16},     {"int16", Scalar::int16},
        {"ushort", Scalar::uint16},  {"uint16", Scalar::uint16},   {"int", Scalar::int32},
        {"int32", Scalar::int32},    {"uint", Scalar::uint32},     {"uint32", Scalar::uint32},
        {"float", Scalar::float32},  {"float32", Scalar::float32}, {"double", Scalar::float64},
        {"float64", Scalar::float64}};
    for (const auto& [text, value] : names)
        if (name == text) return scalar = value, true;
    return false;
}

std::size_t scalar_size(Scalar s)
{
    switch (s) {
    case Scalar::int8:
    case Scalar::uint8: return 1;
    case Scalar::int16:
    case Scalar::uint16: return 2;
    case Scalar::int32:
    case Scalar::uint32:
    case Scalar::float32: return 4;
    case Scalar::float64: return 8;
    }
    return 0;
}

struct Property {
    std::string name;
    Scalar type = Scalar::float64;
    bool is_list = false;
    Scalar count_type = Scalar::uint8;
};

struct Element {
    std::string name;
    std::size_t count = 0;
    std::vector<Property> properties;
};

struct Header {
    enum class Format { ascii, little, big } format = Format::ascii;
    std::vector<Element> elements;
    TissueNames names;
    Label background = 0;
    std::size_t data_start = 0;
};

/// Reads values of the data section, ascii or binary; every failure names the file and the place.
class Cursor {
public:
    Cursor(const std::string& bytes, const Header& header, const std::string& what)
        : bytes_(bytes), at_(header.data_start), format_(header.format), what_(what)
    {
    }
    void locate(const std::string& element, std::size_t item) { element_ = element, item_ = item; }

    double read(Scalar type) { return format_ == Header::Format::ascii ? read_ascii() : read_binary(type); }

private:
    [[noreturn]] void truncated() const
    {
        throw IoError(concat(what_, ": truncated or malformed at ", element_, " ", item_,
                             "; the file is incomplete or corrupt, write it again"));
    }

    double read_ascii()
    {
        while (at_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[at_]))) ++at_;
        if (at_ >= bytes_.size()) truncated();
        std::size_t end = at_;
        while (end < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[end]))) ++end;
        const std::string token = bytes_.substr(at_, end - at_);
        char* stop = nullptr;
        const double value = std::strtod(token.c_str(), &stop);
        if (stop != token.c_str() + token.size()) truncated();
        at_ = end;
        return value;
    }

    double read_binary(Scalar type)
    {
        const std::size_t size = scalar_size(type);
        if (at_ + size > bytes_.size()) truncated();
        unsigned char raw[8];
        std::memcpy(raw, bytes_.data() + at_, size);
        at_ += size;
        if ((format_ == Header::Format::big) == (std::endian::native == std::endian::little))
            for (std::size_t a = 0, b = size - 1; a < b; ++a, --b) std::swap(raw[a], raw[b]);
        return decode(raw, type);
    }

    static double decode(const unsigned char* raw, Scalar type)
    {
        const auto as = [raw]<typename T>(T) {
            T value;
            std::memcpy(&value, raw, sizeof(T));
            return static_cast<double>(value);
        };
        switch (type) {
        case Scalar::int8: return as(std::int8_t{});
        case Scalar::uint8: return as(std::uint8_t{});
        case Scalar::int16: return as(std::int16_t{});
        case Scalar::uint16: return as(std::uint16_t{});
        case Scalar::int32: return as(std::int32_t{});
        case Scalar::uint32: return as(std::uint32_t{});
        case Scalar::float32: return as(float{});
        case Scalar::float64: return as(double{});
        }
        return 0;
    }

    const std::string& bytes_;
    std::size_t at_;
    Header::Format format_;
    const std::string& what_;
    std::string element_ = "header";
    std::size_t item_ = 0;
};

void parse_header_line(const std::string& line, Header& header, const std::string& what)
{
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    const auto bad = [&]() {
        return IoError(concat(what, ": malformed PLY header line '", line, "'; the file is corrupt"));
    };
    if (keyword == "format") {
        std::string format;
        words >> format;
        if (format == "ascii") header.format = Header::Format::ascii;
        else if (format == "binary_little_endian") header.format = Header::Format::little;
        else if (format == "binary_big_endian") header.format = Header::Format::big;
        else throw bad();
    } else if (keyword == "comment") {
        std::string kind;
        long long label = -1;
        words >> kind >> label;
        if ((kind == "tissue" || kind == "background") && words && label >= 0 && label <= 65535) {
            std::string name;
            std::getline(words >> std::ws, name);
            if (kind == "tissue") header.names[static_cast<Label>(label)] = name;
            else header.background = static_cast<Label>(label);
        }
    } else if (keyword == "element") {
        Element element;
        if (!(words >> element.name >> element.count)) throw bad();
        header.elements.push_back(element);
    } else if (keyword == "property") {
        if (header.elements.empty()) throw bad();
        Property property;
        std::string type;
        words >> type;
        if (type == "list") {
            property.is_list = true;
            std::string count_type;
            words >> count_type >> type;
            if (!scalar_from_name(count_type, property.count_type)) throw bad();
        }
        if (!scalar_from_name(type, property.type) || !(words >> property.name)) throw bad();
        header.elements.back().properties.push_back(property);
    } else if (keyword != "obj_info" && !keyword.empty()) {
        throw bad();
    }
}

Header parse_header(const std::string& bytes, const std::string& what)
{
    if (bytes.compare(0, 4, "ply\n") != 0 && bytes.compare(0, 5, "ply\r\n") != 0)
        throw IoError(concat(what, ": not a PLY file (it does not start with 'ply'); check the file or its extension"));
    Header header;
    std::size_t at = bytes.find('\n') + 1;
    while (true) {
        const std::size_t end = bytes.find('\n', at);
        if (end == std::string::npos)
            throw IoError(concat(what, ": the PLY header has no end_header line; the file is truncated"));
        std::string line = bytes.substr(at, end - at);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        at = end + 1;
        if (line == "end_header") break;
        parse_header_line(line, header, what);
    }
    header.data_start = at;
    return header;
}

Label label_value(double value, const std::string& what, std::size_t face)
{
    if (!(value >= 0 && value <= 65535 && value == std::floor(value)))
        throw InputError(concat(what, ": face ", face, " has label ", value, "; labels are integers 0..65535"));
    return static_cast<Label>(value);
}

std::uint32_t index_value(double value, const std::string& what, std::size_t face)
{
    if (!(value >= 0 && value < 4294967295.0 && value == std::floor(value)))
        throw InputError(concat(what, ": face ", face, " has vertex index ", value, "; the file is corrupt"));
    return static_cast<std::uint32_t>(value);
}

void read_face(Cursor& cursor, const Element& element, std::size_t face, InterfaceComplex& complex,
               const std::string& what)
{
    Triangle triangle{};
    LabelPair pair{1, 0};
    bool has_indices = false;
    for (const Property& property : element.properties) {
        if (property.is_list) {
            const double count = cursor.read(property.count_type);
            const bool indices = property.name == "vertex_indices" || property.name == "vertex_index";
            if (indices && count != 3)
                throw IoError(concat(what, ": face ", face, " has ", count,
                                     " vertices; only triangles are supported, "
                                     "triangulate the surface first"));
            if (count < 0 || count > 1e6) throw IoError(concat(what, ": face ", face, " has a corrupt list length"));
            for (int v = 0; v < static_cast<int>(count); ++v) {
                const double value = cursor.read(property.type);
                if (indices) triangle[static_cast<std::size_t>(v)] = index_value(value, what, face);
            }
            has_indices = has_indices || indices;
            continue;
        }
        const double value = cursor.read(property.type);
        if (property.name == "label_a") pair.from = label_value(value, what, face);
        if (property.name == "label_b") pair.to = label_value(value, what, face);
    }
    if (!has_indices)
        throw IoError(concat(what, ": the face element has no vertex_indices list; not a triangle surface"));
    complex.add_triangle(triangle, pair);
}

} // namespace

std::string ply_header(const TissueNames& names, Label background, std::size_t vertices, std::size_t triangles,
                       const std::vector<std::string>& comments, bool ascii)
{
    std::ostringstream header;
    header << "ply\nformat " << (ascii ? "ascii" : "binary_little_endian")
           << " 1.0\ncomment tissuemesh interface complex\n"
           << "comment background " << background << "\n";
    for (const auto& [label, name] : names) header << "comment tissue " << label << " " << name << "\n";
    for (const std::string& comment : comments) header << "comment " << comment << "\n";
    header << "element vertex " << vertices << "\nproperty double x\nproperty double y\n"
           << "property double z\nelement face " << triangles
           << "\nproperty list uint8 uint32 vertex_indices\nproperty uint16 label_a\nproperty uint16 label_b\n"
           << "end_header\n";
    return header.str();
}

void append_ply_vertex(std::string& out, const Vec3& vertex)
{
    for (const double c : vertex) append(out, c);
}

void append_ply_face(std::string& out, const Triangle& triangle, LabelPair side)
{
    append(out, std::uint8_t{3});
    for (const std::uint32_t v : triangle) append(out, v);
    append(out, side.from);
    append(out, side.to);
}

void write_ply(const InterfaceComplex& complex, std::ostream& out, const std::vector<std::string>& comments, bool ascii)
{
    ChunkedOutput chunks(out);
    chunks.text = ply_header(complex.names, complex.background, complex.vertices.size(), complex.triangles.size(),
                             comments, ascii);
    char line[96];
    for (const Vec3& v : complex.vertices) {
        if (ascii)
            chunks.text.append(line, static_cast<std::size_t>(
                                         std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", v[0], v[1], v[2])));
        else append_ply_vertex(chunks.text, v);
        chunks.flush_if_full();
    }
    for (std::size_t t = 0; t < complex.triangles.size(); ++t) {
        const Triangle& f = complex.triangles[t];
        if (ascii)
            chunks.text +=
                concat("3 ", f[0], ' ', f[1], ' ', f[2], ' ', complex.sides[t].from, ' ', complex.sides[t].to, '\n');
        else append_ply_face(chunks.text, f, complex.sides[t]);
        chunks.flush_if_full();
    }
    chunks.flush();
}

InterfaceComplex parse_ply(const std::string& bytes, const std::string& what)
{
    const Header header = parse_header(bytes, what);
    InterfaceComplex complex;
    complex.names = header.names;
    complex.background = header.background;
    Cursor cursor(bytes, header, what);
    for (const Element& element : header.elements) {
        const bool vertex = element.name == "vertex", face = element.name == "face";
        for (std::size_t item = 0; item < element.count; ++item) {
            cursor.locate(element.name, item);
            if (face) {
                read_face(cursor, element, item, complex, what);
                continue;
            }
            Vec3 position{0, 0, 0};
            for (const Property& property : element.properties) {
                const std::size_t count =
                    property.is_list ? static_cast<std::size_t>(cursor.read(property.count_type)) : 1;
                for (std::size_t v = 0; v < count; ++v) {
                    const double value = cursor.read(property.type);
                    if (!vertex || property.is_list) continue;
                    if (property.name == "x") position[0] = value;
                    if (property.name == "y") position[1] = value;
                    if (property.name == "z") position[2] = value;
                }
            }
            if (vertex) complex.vertices.push_back(position);
        }
    }
    return complex;
}

} // namespace tissuemesh::io::detail

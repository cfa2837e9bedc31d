#include "io/detail/stl_format.h"

#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>

#include "core/error.h"
#include "io/detail/byte_reader.h"
#include "io/detail/chunked_output.h"

namespace tissuemesh::io::detail {
namespace {

static_assert(std::endian::native == std::endian::little, "STL code assumes a little-endian host");

template <typename T>
void append(std::string& out, T value)
{
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    out.append(bytes, sizeof(T));
}

template <typename T>
T read_at(const std::string& bytes, std::size_t at)
{
    T value;
    std::memcpy(&value, bytes.data() + at, sizeof(T));
    return value;
}

constexpr std::size_t header_size = 84; // 80-byte header + uint32 triangle count
constexpr std::size_t record_size = 50; // normal, 3 corners (12 float32) + uint16 attribute

} // namespace

namespace {

Vec3 unit_normal(const Vec3& a, const Vec3& b, const Vec3& c)
{
    const Vec3 n = cross(b - a, c - a);
    const double length = norm(n);
    return length > 0 ? (1.0 / length) * n : n;
}

void write_ascii_stl(const InterfaceComplex& complex, ChunkedOutput& chunks)
{
    chunks.text = "solid tissuemesh\n";
    char line[128];
    auto add = [&](const char* format, const Vec3& v) {
        const int length =
            std::snprintf(line, sizeof line, format, static_cast<double>(static_cast<float>(v[0])),
                          static_cast<double>(static_cast<float>(v[1])), static_cast<double>(static_cast<float>(v[2])));
        chunks.text.append(line, static_cast<std::size_t>(length));
    };
    for (const Triangle& t : complex.triangles) {
        const Vec3 &a = complex.vertices[t[0]], &b = complex.vertices[t[1]], &c = complex.vertices[t[2]];
        add("facet normal %.9g %.9g %.9g\n outer loop\n", unit_normal(a, b, c));
        for (const Vec3& v : {a, b, c}) add("  vertex %.9g %.9g %.9g\n", v);
        chunks.text += " endloop\nendfacet\n";
        chunks.flush_if_full();
    }
    chunks.text += "endsolid tissuemesh\n";
    chunks.flush();
}

} // namespace

void write_stl(const InterfaceComplex& complex, std::ostream& stream, bool ascii)
{
    ChunkedOutput chunks(stream);
    if (ascii) return write_ascii_stl(complex, chunks);
    std::string& out = chunks.text;
    out.assign(80, ' ');
    out.replace(0, 31, "tissuemesh binary STL surface  ");
    append(out, static_cast<std::uint32_t>(complex.triangles.size()));
    for (const Triangle& t : complex.triangles) {
        const Vec3 &a = complex.vertices[t[0]], &b = complex.vertices[t[1]], &c = complex.vertices[t[2]];
        for (const Vec3& v : {unit_normal(a, b, c), a, b, c})
            for (const double x : v) append(out, static_cast<float>(x));
        append(out, std::uint16_t{0});
        chunks.flush_if_full();
    }
    chunks.flush();
}

/// ASCII STL: "solid", then "facet normal n n n / outer loop / vertex x y z (3x) / endloop / endfacet".
InterfaceComplex parse_ascii_stl(const std::string& text, const std::string& what)
{
    ByteReader in(text, what);
    in.expect("solid");
    in.rest_of_line();
    InterfaceComplex complex;
    std::map<Vec3, std::uint32_t> index_of;
    std::string_view word = in.word();
    for (; word == "facet"; word = in.word()) {
        in.expect("normal");
        for (int c = 0; c < 3; ++c) in.real("a normal component");
        in.expect("outer");
        in.expect("loop");
        Triangle triangle{};
        for (std::uint32_t& corner : triangle) {
            in.expect("vertex");
            const Vec3 p{in.real("a coordinate"), in.real("a coordinate"), in.real("a coordinate")};
            const auto [it, fresh] = index_of.try_emplace(p, static_cast<std::uint32_t>(complex.vertices.size()));
            if (fresh) complex.vertices.push_back(p);
            corner = it->second;
        }
        in.expect("endloop");
        in.expect("endfacet");
        complex.add_triangle(triangle, {1, 0});
    }
    if (word != "endsolid")
        in.fail(concat("expected facet or endsolid but found \"", word.substr(0, 40), "\""), "the STL file is corrupt");
    return complex;
}

InterfaceComplex parse_stl(const std::string& bytes, const std::string& what)
{
    const bool binary_size =
        bytes.size() >= header_size && bytes.size() == header_size + record_size * read_at<std::uint32_t>(bytes, 80);
    if (!binary_size && bytes.compare(0, 5, "solid") == 0) return parse_ascii_stl(bytes, what);
    if (bytes.size() < header_size)
        throw IoError(concat(what, ": ", bytes.size(), " bytes is too short for a binary STL file; it is truncated"));
    const std::size_t count = read_at<std::uint32_t>(bytes, 80);
    if (bytes.size() != header_size + record_size * count) {
        throw IoError(concat(what, ": size does not match its triangle count; the file is truncated (", count,
                             " triangles announced, ", bytes.size(), " bytes)"));
    }
    InterfaceComplex complex;
    std::map<std::array<float, 3>, std::uint32_t> index_of;
    for (std::size_t t = 0; t < count; ++t) {
        Triangle triangle{};
        for (std::size_t c = 0; c < 3; ++c) {
            const std::size_t at = header_size + record_size * t + 12 * (c + 1);
            const std::array<float, 3> p{read_at<float>(bytes, at), read_at<float>(bytes, at + 4),
                                         read_at<float>(bytes, at + 8)};
            const auto [it, fresh] = index_of.try_emplace(p, static_cast<std::uint32_t>(complex.vertices.size()));
            if (fresh) complex.vertices.push_back({p[0], p[1], p[2]});
            triangle[c] = it->second;
        }
        complex.add_triangle(triangle, {1, 0});
    }
    return complex;
}

} // namespace tissuemesh::io::detail

#include "io/detail/obj_format.h"

#include <charconv>
#include <cstdio>

#include "core/error.h"
#include "io/detail/byte_reader.h"
#include "io/detail/chunked_output.h"
#include "io/detail/msh_common.h"
#include "io/detail/text_records.h"

namespace tissuemesh::io::detail {
namespace {

/// The vertex index of an `f` corner ("12", "12/3", "12//4", "-1").
std::uint32_t corner(std::string_view token, std::size_t vertices, const ByteReader& in)
{
    const std::string_view number = token.substr(0, token.find('/'));
    long long value = 0;
    const auto [end, error] = std::from_chars(number.data(), number.data() + number.size(), value);
    if (error != std::errc() || end != number.data() + number.size() || value == 0)
        in.fail(concat("\"", token.substr(0, 40), "\" is not a face corner"), "the file is corrupt; write it again");
    const long long index = value > 0 ? value - 1 : static_cast<long long>(vertices) + value;
    if (index < 0 || static_cast<unsigned long long>(index) >= vertices)
        throw InputError(concat(in.what(), ": face corner ", value, " refers to none of the ", vertices,
                                " vertices defined before it (at byte ", in.position(), "); the file is corrupt"));
    return static_cast<std::uint32_t>(index);
}

/// {from, to} of a group "tissues_<from>_<to>", or {1, 0}.
LabelPair group_pair(std::string_view name)
{
    unsigned from = 0, to = 0;
    const std::string text(name);
    char tail = 0;
    if (std::sscanf(text.c_str(), "tissues_%u_%u%c", &from, &to, &tail) == 2 && from <= 65535 && to <= 65535)
        return {static_cast<Label>(from), static_cast<Label>(to)};
    return {1, 0};
}

} // namespace

void write_obj(const InterfaceComplex& complex, std::ostream& stream)
{
    ChunkedOutput chunks(stream);
    std::string& out = chunks.text;
    out = "# tissuemesh interface complex, lengths in mm\n" + format_name_comments(complex.names, "#");
    for (const Vec3& v : complex.vertices) {
        out += 'v';
        for (const double c : v) out += ' ', append_real(out, c);
        out += '\n';
        chunks.flush_if_full();
    }
    for (std::size_t t = 0; t < complex.triangles.size(); ++t) {
        if (t == 0 || !(complex.sides[t] == complex.sides[t - 1]))
            out += concat("g tissues_", complex.sides[t].from, "_", complex.sides[t].to, "\n");
        const Triangle& tri = complex.triangles[t];
        out += concat("f ", tri[0] + 1, ' ', tri[1] + 1, ' ', tri[2] + 1, '\n');
        chunks.flush_if_full();
    }
    chunks.flush();
}

InterfaceComplex parse_obj(const std::string& text, const std::string& what)
{
    const std::string clean = without_comments(text, "#");
    ByteReader in(clean, what);
    InterfaceComplex complex;
    read_name_comments(text, "#", complex.names);
    LabelPair pair{1, 0};
    while (in.remaining() > 0) {
        const std::string line(in.rest_of_line());
        std::string line_copy = line;
        ByteReader record(line_copy, what);
        const std::string_view keyword = record.word();
        if (keyword == "v") {
            Vec3 v{};
            for (double& c : v) c = record.real("a coordinate");
            complex.vertices.push_back(v);
        } else if (keyword == "f") {
            Triangle tri{};
            std::size_t corners = 0;
            for (std::string_view token = record.word(); !token.empty(); token = record.word(), ++corners)
                if (corners < 3) tri[corners] = corner(token, complex.vertices.size(), in);
            if (corners != 3)
                in.fail(concat("a face has ", corners, " corners"),
                        "only triangles are supported: triangulate the surface first");
            complex.add_triangle(tri, pair);
        } else if (keyword == "g" || keyword == "o") {
            pair = group_pair(record.word());
        }
    }
    return complex;
}

} // namespace tissuemesh::io::detail

#include "io/detail/off_format.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/error.h"
#include "io/detail/chunked_output.h"

namespace tissuemesh::io::detail {
namespace {

/// Whitespace-separated tokens of OFF text, skipping `#` comments.
class Tokens {
public:
    Tokens(const std::string& text, const std::string& what) : what_(what)
    {
        std::istringstream lines(text);
        std::string line;
        std::string clean;
        while (std::getline(lines, line)) clean += line.substr(0, line.find('#')) + '\n';
        stream_.str(clean);
    }
    std::string word()
    {
        std::string token;
        if (!(stream_ >> token)) throw IoError(concat(what_, ": truncated; the OFF file ends early, write it again"));
        return token;
    }
    double number()
    {
        const std::string token = word();
        std::size_t used = 0;
        double value = 0;
        try {
            value = std::stod(token, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != token.size())
            throw IoError(concat(what_, ": '", token, "' is not a number; the OFF file is corrupt"));
        return value;
    }

private:
    std::istringstream stream_;
    const std::string& what_;
};

std::size_t count_value(double value, const std::string& what)
{
    if (!(value >= 0 && value < 4294967295.0 && value == std::floor(value)))
        throw IoError(concat(what, ": count or index ", value, " is not a valid integer; the OFF file is corrupt"));
    return static_cast<std::size_t>(value);
}

} // namespace

void write_off(const InterfaceComplex& complex, std::ostream& stream)
{
    ChunkedOutput chunks(stream);
    std::string& out = chunks.text;
    out = concat("OFF\n", complex.vertices.size(), " ", complex.triangles.size(), " 0\n");
    char buffer[96];
    for (const Vec3& v : complex.vertices) {
        std::snprintf(buffer, sizeof(buffer), "%.17g %.17g %.17g\n", v[0], v[1], v[2]);
        out += buffer;
        chunks.flush_if_full();
    }
    for (const Triangle& t : complex.triangles) {
        out += concat("3 ", t[0], " ", t[1], " ", t[2], "\n");
        chunks.flush_if_full();
    }
    chunks.flush();
}

InterfaceComplex parse_off(const std::string& text, const std::string& what)
{
    Tokens tokens(text, what);
    if (tokens.word() != "OFF")
        throw IoError(
            concat(what, ": not an OFF file (it does not start with 'OFF'); check the file or its extension"));
    const std::size_t vertices = count_value(tokens.number(), what);
    const std::size_t faces = count_value(tokens.number(), what);
    tokens.number(); // edge count, unused
    InterfaceComplex complex;
    for (std::size_t v = 0; v < vertices; ++v)
        complex.vertices.push_back({tokens.number(), tokens.number(), tokens.number()});
    for (std::size_t f = 0; f < faces; ++f) {
        const std::size_t corners = count_value(tokens.number(), what);
        if (corners != 3)
            throw IoError(concat(what, ": face ", f, " has ", corners,
                                 " vertices; only triangles are supported, "
                                 "triangulate the surface first"));
        Triangle triangle{};
        for (std::uint32_t& index : triangle) index = static_cast<std::uint32_t>(count_value(tokens.number(), what));
        complex.add_triangle(triangle, {1, 0});
    }
    return complex;
}

} // namespace tissuemesh::io::detail

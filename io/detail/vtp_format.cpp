#include "io/detail/vtp_format.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "core/error.h"
#include "io/detail/chunked_output.h"

namespace tissuemesh::io::detail {
namespace {

void append_number(std::string& out, double value)
{
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%.17g ", value);
    out += buffer;
}

/// The numbers of the DataArray whose opening tag contains `marker` (a Name="..." or a section start).
std::vector<double> data_array(const std::string& text, const std::string& section, const std::string& name,
                               const std::string& what, bool required)
{
    std::size_t from = 0;
    if (!section.empty()) {
        from = text.find("<" + section);
        if (from == std::string::npos) {
            if (!required) return {};
            throw IoError(concat(what, ": no <", section, "> section; not a triangle PolyData file"));
        }
    }
    std::size_t tag = text.find("<DataArray", from);
    if (!name.empty())
        while (tag != std::string::npos &&
               text.substr(tag, text.find('>', tag) - tag).find("Name=\"" + name + "\"") == std::string::npos)
            tag = text.find("<DataArray", tag + 1);
    if (tag == std::string::npos) {
        if (!required) return {};
        throw IoError(concat(what, ": no DataArray ", name.empty() ? section : name, "; not a triangle PolyData file"));
    }
    const std::size_t open_end = text.find('>', tag);
    const std::size_t close = text.find("</DataArray>", tag);
    if (open_end == std::string::npos || close == std::string::npos || close < open_end)
        throw IoError(concat(what, ": DataArray ", name, " is not closed; the file is truncated"));
    const std::string open = text.substr(tag, open_end - tag);
    if (open.find("format=\"ascii\"") == std::string::npos)
        throw IoError(concat(what, ": DataArray ", name, " is not ascii; only ascii .vtp is read, save it as ascii"));
    std::vector<double> values;
    const char* at = text.c_str() + open_end + 1;
    const char* end = text.c_str() + close;
    while (true) {
        while (at < end && std::isspace(static_cast<unsigned char>(*at))) ++at;
        if (at >= end) break;
        char* stop = nullptr;
        const double value = std::strtod(at, &stop);
        if (stop == at || stop > end) throw IoError(concat(what, ": DataArray ", name, " holds a non-number"));
        values.push_back(value);
        at = stop;
    }
    return values;
}

std::size_t piece_count(const std::string& text, const std::string& attribute, const std::string& what)
{
    const std::size_t piece = text.find("<Piece");
    const std::size_t at = piece == std::string::npos ? piece : text.find(attribute + "=\"", piece);
    if (at == std::string::npos)
        throw IoError(concat(what, ": no <Piece ", attribute, "=...>; not a VTK PolyData file or truncated"));
    return static_cast<std::size_t>(std::strtoull(text.c_str() + at + attribute.size() + 2, nullptr, 10));
}

} // namespace

void write_vtp(const InterfaceComplex& complex, std::ostream& stream)
{
    const std::size_t n = complex.triangles.size();
    ChunkedOutput chunks(stream);
    std::string& out = chunks.text;
    out = concat("<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" "
                 "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<PolyData>\n<Piece NumberOfPoints=\"",
                 complex.vertices.size(),
                 "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
                 "NumberOfPolys=\"",
                 n,
                 "\">\n<Points>\n<DataArray type=\"Float64\" "
                 "NumberOfComponents=\"3\" format=\"ascii\">\n");
    for (const Vec3& v : complex.vertices) {
        for (const double c : v) append_number(out, c);
        out += '\n';
        chunks.flush_if_full();
    }
    out += "</DataArray>\n</Points>\n<Polys>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (const Triangle& t : complex.triangles) {
        out += concat(t[0], ' ', t[1], ' ', t[2], '\n');
        chunks.flush_if_full();
    }
    out += "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t t = 1; t <= n; ++t) {
        out += concat(3 * t, t % 16 == 0 ? '\n' : ' ');
        chunks.flush_if_full();
    }
    out += "\n</DataArray>\n</Polys>\n<CellData Scalars=\"label_a\">\n";
    for (const bool first : {true, false}) {
        out += concat("<DataArray type=\"UInt16\" Name=\"", first ? "label_a" : "label_b", "\" format=\"ascii\">\n");
        for (std::size_t t = 0; t < n; ++t) {
            out += concat(first ? complex.sides[t].from : complex.sides[t].to, t % 32 == 31 ? '\n' : ' ');
            chunks.flush_if_full();
        }
        out += "\n</DataArray>\n";
    }
    out += "</CellData>\n</Piece>\n</PolyData>\n</VTKFile>\n";
    chunks.flush();
}

InterfaceComplex parse_vtp(const std::string& text, const std::string& what)
{
    if (text.find("<VTKFile") == std::string::npos || text.find("type=\"PolyData\"") == std::string::npos)
        throw IoError(concat(what, ": not a VTK XML PolyData file (no <VTKFile type=\"PolyData\">); check the file"));
    const std::size_t points = piece_count(text, "NumberOfPoints", what);
    const std::size_t polys = piece_count(text, "NumberOfPolys", what);
    const std::vector<double> xyz = data_array(text, "Points", "", what, true);
    const std::vector<double> connectivity = data_array(text, "Polys", "connectivity", what, true);
    const std::vector<double> offsets = data_array(text, "Polys", "offsets", what, true);
    const std::vector<double> label_a = data_array(text, "CellData", "label_a", what, false);
    const std::vector<double> label_b = data_array(text, "CellData", "label_b", what, false);
    if (xyz.size() != 3 * points || offsets.size() != polys || connectivity.size() != 3 * polys)
        throw IoError(concat(what, ": ", points, " points and ", polys, " polygons announced but the arrays hold ",
                             xyz.size(), " coordinates and ", connectivity.size(),
                             " indices (only triangles are "
                             "read); the file is truncated or not a triangle surface"));
    const bool labelled = label_a.size() == polys && label_b.size() == polys;
    InterfaceComplex complex;
    for (std::size_t p = 0; p < points; ++p) complex.vertices.push_back({xyz[3 * p], xyz[3 * p + 1], xyz[3 * p + 2]});
    for (std::size_t t = 0; t < polys; ++t) {
        if (offsets[t] != static_cast<double>(3 * (t + 1)))
            throw IoError(concat(what, ": polygon ", t, " is not a triangle; only triangle surfaces are read"));
        Triangle triangle{};
        for (std::size_t c = 0; c < 3; ++c) {
            const double index = connectivity[3 * t + c];
            if (!(index >= 0 && index < 4294967295.0 && index == std::floor(index)))
                throw InputError(concat(what, ": polygon ", t, " has vertex index ", index, "; the file is corrupt"));
            triangle[c] = static_cast<std::uint32_t>(index);
        }
        LabelPair pair{1, 0};
        if (labelled) {
            for (const double l : {label_a[t], label_b[t]})
                if (!(l >= 0 && l <= 65535 && l == std::floor(l)))
                    throw InputError(concat(what, ": polygon ", t, " has label ", l, "; labels are integers 0..65535"));
            pair = {static_cast<Label>(label_a[t]), static_cast<Label>(label_b[t])};
        }
        complex.add_triangle(triangle, pair);
    }
    return complex;
}

} // namespace tissuemesh::io::detail

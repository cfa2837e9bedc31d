// .vtu files in every encoding the VTK XML format allows, written here (our writer makes only two of
// them) to test that read_vtu() reads all: ASCII, inline base64, appended raw or base64, each with or without
// zlib blocks, UInt32 or UInt64 headers, 32- or 64-bit integers and floats.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>
#include <zlib.h>

#include "core/error.h"
#include "core/tet_mesh.h"
#include "render/report_html.h"

namespace tissuemesh::testing {

struct VtuVariant {
    std::string format = "appended"; ///< "ascii", "binary" (inline base64) or "appended"
    bool base64_appended = false;    ///< appended data as base64 instead of raw
    bool compressed = false;         ///< zlib blocks
    bool header64 = true;            ///< UInt64 headers (else UInt32)
    bool wide = true;                ///< Int64 and Float64 (else Int32 and Float32)
    std::size_t block_bytes = 64;    ///< zlib block size: small, so that arrays span several blocks
};

class VtuVariantWriter {
public:
    explicit VtuVariantWriter(VtuVariant variant) : v_(std::move(variant)) {}

    /// A whole file of `mesh` with cell data "tissue" (Int32) and a point array "phi" = x + 2 y (floats).
    std::string file(const TetMesh& mesh)
    {
        std::vector<double> xyz, phi;
        for (const Vec3& p : mesh.vertices) xyz.insert(xyz.end(), p.begin(), p.end()), phi.push_back(p[0] + 2 * p[1]);
        std::vector<std::int64_t> corners, offsets, labels(mesh.tet_labels.begin(), mesh.tet_labels.end());
        for (const Tet& t : mesh.tets)
            corners.insert(corners.end(), t.begin(), t.end()),
                offsets.push_back(static_cast<std::int64_t>(corners.size()));
        std::string xml = concat("<?xml version=\"1.0\"?>\n<!-- variant -->\n<VTKFile type=\"UnstructuredGrid\" "
                                 "version=\"1.0\" byte_order=\"LittleEndian\"",
                                 v_.header64 ? " header_type=\"UInt64\"" : "",
                                 v_.compressed ? " compressor=\"vtkZLibDataCompressor\"" : "",
                                 ">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"", mesh.vertices.size(),
                                 "\" NumberOfCells=\"", mesh.tets.size(), "\">\n");
        xml += "<Points>\n" + floats("", 3, xyz) + "</Points>\n<Cells>\n" + integers("connectivity", corners, v_.wide) +
               integers("offsets", offsets, v_.wide) +
               bytes_array("types", std::vector<std::uint8_t>(mesh.tets.size(), 10), "UInt8") + "</Cells>\n";
        xml += "<PointData>\n" + floats("phi", 1, phi) + "</PointData>\n<CellData>\n" +
               integers("tissue", labels, false) + "</CellData>\n";
        xml += "</Piece>\n</UnstructuredGrid>\n";
        if (v_.format == "appended")
            xml += concat("<AppendedData encoding=\"", v_.base64_appended ? "base64" : "raw", "\">\n   _", appended_,
                          "\n</AppendedData>\n");
        return xml + "</VTKFile>\n";
    }

private:
    std::string floats(const std::string& name, int components, const std::vector<double>& values)
    {
        if (v_.wide) return bytes_array(name, values, "Float64", components);
        return bytes_array(name, std::vector<float>(values.begin(), values.end()), "Float32", components);
    }
    std::string integers(const std::string& name, const std::vector<std::int64_t>& values, bool wide)
    {
        if (wide) return bytes_array(name, values, "Int64");
        return bytes_array(name, std::vector<std::int32_t>(values.begin(), values.end()), "Int32");
    }

    template <typename T>
    std::string bytes_array(const std::string& name, const std::vector<T>& values, const char* type, int components = 1)
    {
        std::string tag = concat("<DataArray type=\"", type, "\"", name.empty() ? "" : " Name=\"" + name + "\"",
                                 " NumberOfComponents=\"", components, "\" format=\"", v_.format, "\"");
        if (v_.format == "ascii") {
            tag += ">\n";
            for (const T& value : values) tag += concat(+value, ' ');
            return tag + "\n</DataArray>\n";
        }
        const std::string data(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
        const std::string header = header_of(data), body = v_.compressed ? deflate_blocks(data) : data;
        // VTK encodes header and data as two base64 streams; inline, the data follows on the same line.
        const std::string encoded = render::base64(header) + render::base64(body);
        if (v_.format == "binary") return tag + ">\n  " + encoded + "\n</DataArray>\n";
        tag += concat(" offset=\"", appended_.size(), "\"/>\n");
        appended_ += v_.base64_appended ? encoded : header + body;
        return tag;
    }

    void word(std::string& out, std::uint64_t value) const
    {
        if (v_.header64) return out.append(reinterpret_cast<const char*>(&value), 8), void();
        const auto narrow = static_cast<std::uint32_t>(value);
        out.append(reinterpret_cast<const char*>(&narrow), 4);
    }

    std::string header_of(const std::string& data)
    {
        std::string header;
        if (!v_.compressed) return word(header, data.size()), header;
        const std::size_t blocks = (data.size() + v_.block_bytes - 1) / v_.block_bytes;
        word(header, blocks), word(header, v_.block_bytes),
            word(header, blocks == 0 ? 0 : data.size() - (blocks - 1) * v_.block_bytes);
        packed_.clear();
        for (std::size_t b = 0; b < blocks; ++b) {
            const std::size_t size = std::min(v_.block_bytes, data.size() - b * v_.block_bytes);
            uLongf length = compressBound(static_cast<uLong>(size));
            std::string out(length, '\0');
            compress2(reinterpret_cast<Bytef*>(out.data()), &length,
                      reinterpret_cast<const Bytef*>(data.data() + b * v_.block_bytes), static_cast<uLong>(size), 6);
            out.resize(length);
            word(header, length);
            packed_ += out;
        }
        return header;
    }
    std::string deflate_blocks(const std::string&) const { return packed_; }

    VtuVariant v_;
    std::string appended_, packed_;
};

} // namespace tissuemesh::testing

// The parts of VTK's XML file format (.vtu, .vtp) a reader needs: the tags around the data, and the
// DataArrays decoded from any of their encodings (ASCII; base64 inline; appended raw or base64; each with or
// without zlib blocks, UInt32 or UInt64 headers) into numbers. Every size a header claims is checked
// against the bytes that hold it, or (compressed) against zlib's largest ratio, before anything is allocated.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace tissuemesh::io::detail {

/// One <DataArray> as found in the file.
struct VtkDataArray {
    std::string section;                           ///< the enclosing element: "Points", "Cells", "PointData", ...
    std::map<std::string, std::string> attributes; ///< as written (type, Name, format, offset, NumberOfComponents)
    std::string_view text;                         ///< between its tags (ASCII or base64 data); empty when self-closing
    std::size_t at = 0;                            ///< byte position of its tag, for messages

    std::string attribute(const std::string& key) const; ///< "" when absent
    std::string name() const { return attribute("Name"); }
    bool integer() const; ///< an Int* or UInt* type
};

/// The tags of a VTK XML file and where its appended data is.
struct VtkXmlFile {
    std::string what;                                       ///< the file, for messages
    std::map<std::string, std::string> vtk_file;            ///< attributes of <VTKFile>
    std::vector<std::map<std::string, std::string>> pieces; ///< attributes of each <Piece>
    std::vector<VtkDataArray> arrays;                       ///< in file order
    std::string appended_encoding;                          ///< "raw", "base64", or "" without <AppendedData>
    std::string_view appended;                              ///< from just after the '_' mark to the end of the data
    std::size_t appended_at = 0;                            ///< byte position of the '_' mark
};

/// Scans the tags of `bytes` (which must outlive the result). Checks byte order (little-endian only),
/// header type (UInt32, UInt64) and compressor (none, vtkZLibDataCompressor).
/// @throws IoError "file: problem (at byte N); fix" on malformed XML or unsupported settings
VtkXmlFile scan_vtk_xml(const std::string& bytes, const std::string& what);

/// The `values` numbers of `array` (entries x components, row by row) as doubles, whatever its type
/// (Int8..UInt64, Float32, Float64) and encoding. `items` names the entries in messages ("points").
/// @throws IoError when the array holds another number of values, is truncated or corrupt, or its type
///         or format is unknown
std::vector<double> decode_data_array(const VtkXmlFile& file, const VtkDataArray& array, std::size_t values,
                                      const char* items);

/// Standard base64, possibly several padded streams one after the other (VTK encodes a block's header and
/// its data separately); whitespace is skipped. Returns false on a character outside the alphabet.
bool decode_base64(std::string_view text, std::string& out);

} // namespace tissuemesh::io::detail

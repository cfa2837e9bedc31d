#include "io/detail/vtk_xml.h"

#include <cctype>

#include "core/error.h"

namespace tissuemesh::io::detail {
namespace {

[[noreturn]] void fail(const std::string& what, std::size_t at, const std::string& problem, const std::string& fix)
{
    throw IoError(concat(what, ": ", problem, " (at byte ", at, "); ", fix));
}

bool is_space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }
bool is_name_char(char c)
{
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == ':' || c == '-' || c == '.';
}

/// A start tag `<name key="value" ...>` or `<name .../>` read from just after its '<'.
struct StartTag {
    std::string name;
    std::map<std::string, std::string> attributes;
    bool self_closing = false;
    std::size_t end = 0; ///< just after its '>'
};

StartTag read_start_tag(std::string_view xml, std::size_t at, const std::string& what)
{
    StartTag tag;
    std::size_t i = at + 1;
    while (i < xml.size() && is_name_char(xml[i])) tag.name += xml[i++];
    if (tag.name.empty()) fail(what, at, "a '<' starts no tag name", "the file is not VTK XML or is corrupt");
    while (true) {
        while (i < xml.size() && is_space(xml[i])) ++i;
        if (i >= xml.size()) fail(what, at, concat("the tag <", tag.name, "> is not closed"), "the file is truncated");
        if (xml[i] == '>') break;
        if (xml[i] == '/' && i + 1 < xml.size() && xml[i + 1] == '>') {
            tag.self_closing = true;
            ++i;
            break;
        }
        std::string key;
        while (i < xml.size() && is_name_char(xml[i])) key += xml[i++];
        while (i < xml.size() && is_space(xml[i])) ++i;
        if (key.empty() || i + 1 >= xml.size() || xml[i] != '=')
            fail(what, i, concat("the tag <", tag.name, "> has a malformed attribute"),
                 "the file is not VTK XML or is corrupt");
        ++i;
        while (i < xml.size() && is_space(xml[i])) ++i;
        const char quote = i < xml.size() ? xml[i] : '\0';
        const std::size_t close = quote == '"' || quote == '\'' ? xml.find(quote, i + 1) : std::string_view::npos;
        if (close == std::string_view::npos)
            fail(what, i, concat("attribute ", key, " of <", tag.name, "> has no quoted value"), "the file is corrupt");
        tag.attributes[key] = std::string(xml.substr(i + 1, close - i - 1));
        i = close + 1;
    }
    tag.end = i + 1;
    return tag;
}

/// Moves past a comment, declaration or processing instruction starting at `at`; returns npos when none starts there.
std::size_t skip_markup(std::string_view xml, std::size_t at, const std::string& what)
{
    const auto past = [&](std::string_view end) {
        const std::size_t found = xml.find(end, at);
        if (found == std::string_view::npos)
            fail(what, at, concat("no ", end, " closes the markup"), "the file is truncated");
        return found + end.size();
    };
    if (xml.substr(at, 4) == "<!--") return past("-->");
    if (xml.substr(at, 2) == "<?") return past("?>");
    if (xml.substr(at, 2) == "<!") return past(">");
    return std::string_view::npos;
}

void check_settings(const VtkXmlFile& file, std::size_t at)
{
    const auto value = [&](const char* key) {
        const auto f = file.vtk_file.find(key);
        return f == file.vtk_file.end() ? std::string() : f->second;
    };
    if (!value("byte_order").empty() && value("byte_order") != "LittleEndian")
        fail(file.what, at, concat("byte order ", value("byte_order"), " is not read"),
             "save the file as LittleEndian (ParaView, meshio and VTK's default)");
    if (!value("header_type").empty() && value("header_type") != "UInt32" && value("header_type") != "UInt64")
        fail(file.what, at, concat("header type ", value("header_type"), " is not VTK's"),
             "save with header_type UInt32 or UInt64");
    if (!value("compressor").empty() && value("compressor") != "vtkZLibDataCompressor")
        fail(file.what, at, concat("compressor ", value("compressor"), " is not read"),
             "save uncompressed or with zlib compression");
}

void read_appended(const std::string& bytes, std::size_t at, VtkXmlFile& file)
{
    const StartTag tag = read_start_tag(bytes, at, file.what);
    const auto encoding = tag.attributes.find("encoding");
    file.appended_encoding = encoding == tag.attributes.end() ? "raw" : encoding->second;
    if (file.appended_encoding != "raw" && file.appended_encoding != "base64")
        fail(file.what, at, concat("appended data encoding \"", file.appended_encoding, "\" is unknown"),
             "save as raw or base64");
    const std::size_t mark = bytes.find('_', tag.end);
    if (mark == std::string::npos)
        fail(file.what, tag.end, "the appended data has no '_' mark", "the file is truncated");
    std::size_t end = bytes.size();
    if (file.appended_encoding == "base64") {
        end = bytes.rfind("</AppendedData>");
        if (end == std::string::npos || end < mark)
            fail(file.what, mark, "no </AppendedData> after the appended data", "the file is truncated");
    }
    file.appended = std::string_view(bytes).substr(mark + 1, end - mark - 1);
    file.appended_at = mark;
}

} // namespace

std::string VtkDataArray::attribute(const std::string& key) const
{
    const auto found = attributes.find(key);
    return found == attributes.end() ? std::string() : found->second;
}

bool VtkDataArray::integer() const
{
    const std::string type = attribute("type");
    return type.rfind("Int", 0) == 0 || type.rfind("UInt", 0) == 0;
}

VtkXmlFile scan_vtk_xml(const std::string& bytes, const std::string& what)
{
    VtkXmlFile file;
    file.what = what;
    const std::size_t appended = bytes.find("<AppendedData");
    const std::string_view xml = std::string_view(bytes).substr(0, appended);
    std::vector<std::string> open; // enclosing elements
    bool seen_vtk_file = false;
    for (std::size_t at = xml.find('<'); at != std::string_view::npos; at = xml.find('<', at)) {
        if (const std::size_t next = skip_markup(xml, at, what); next != std::string_view::npos) {
            at = next;
            continue;
        }
        if (xml.substr(at, 2) == "</") {
            const std::size_t end = xml.find('>', at);
            if (end == std::string_view::npos) fail(what, at, "an end tag is not closed", "the file is truncated");
            const std::string name(xml.substr(at + 2, end - at - 2));
            if (open.empty() || open.back() != name)
                fail(what, at, concat("</", name, "> closes ", open.empty() ? "nothing" : "<" + open.back() + ">"),
                     "the file is corrupt");
            open.pop_back();
            at = end + 1;
            continue;
        }
        const StartTag tag = read_start_tag(xml, at, what);
        if (!seen_vtk_file && tag.name != "VTKFile")
            fail(what, at, concat("the first tag is <", tag.name, ">, not <VTKFile>"), "check the file");
        if (tag.name == "VTKFile") file.vtk_file = tag.attributes, seen_vtk_file = true, check_settings(file, at);
        if (tag.name == "Piece") file.pieces.push_back(tag.attributes);
        if (tag.name == "DataArray") {
            VtkDataArray array{open.empty() ? "" : open.back(), tag.attributes, {}, at};
            at = tag.end;
            if (!tag.self_closing) {
                const std::size_t close = xml.find("</DataArray>", tag.end);
                if (close == std::string_view::npos)
                    fail(what, at, concat("DataArray \"", array.name(), "\" is not closed"), "the file is truncated");
                array.text = xml.substr(tag.end, close - tag.end);
                at = close + 12;
            }
            file.arrays.push_back(std::move(array));
            continue;
        }
        if (!tag.self_closing) open.push_back(tag.name);
        at = tag.end;
    }
    if (!seen_vtk_file) fail(what, 0, "no <VTKFile> tag", "not a VTK XML file; check the file or its extension");
    // Every element closed: <AppendedData> inside <VTKFile>, and the file's last tag </VTKFile> (a cut file ends early).
    const bool closed = appended == std::string::npos
                            ? open.empty()
                            : open.size() == 1 && bytes.rfind("</VTKFile>") != std::string::npos &&
                                  bytes.rfind("</VTKFile>") > appended;
    if (!closed)
        fail(what, bytes.size(), concat("the file ends inside <", open.empty() ? "VTKFile" : open.back(), ">"),
             "the file is truncated; write it again");
    if (appended != std::string::npos) read_appended(bytes, appended, file);
    return file;
}

} // namespace tissuemesh::io::detail

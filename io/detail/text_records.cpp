#include "io/detail/text_records.h"

#include <charconv>
#include <sstream>

#include "core/error.h"

namespace tissuemesh::io::detail {

std::string without_comments(const std::string& text, std::string_view marker)
{
    std::string clean = text;
    for (std::size_t at = clean.find(marker); at != std::string::npos; at = clean.find(marker, at)) {
        const std::size_t end = std::min(clean.find('\n', at), clean.size());
        for (std::size_t i = at; i < end; ++i) clean[i] = ' ';
        at = end;
    }
    return clean;
}

void read_name_comments(const std::string& text, std::string_view marker, TissueNames& names)
{
    const std::string key = concat(marker, " tissuemesh tissue ");
    for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + 1)) {
        const std::size_t start = at + key.size();
        const std::size_t end = std::min(text.find('\n', start), text.size());
        const std::string line = text.substr(start, end - start);
        unsigned label = 0;
        const auto [rest, error] = std::from_chars(line.data(), line.data() + line.size(), label);
        if (error != std::errc() || label > 65535 || rest == line.data() + line.size() || *rest != ' ') continue;
        std::string name(rest + 1, line.data() + line.size());
        if (!name.empty() && name.back() == '\r') name.pop_back();
        names[static_cast<Label>(label)] = name;
    }
}

std::string format_name_comments(const TissueNames& names, std::string_view marker)
{
    std::string out;
    for (const auto& [label, name] : names) out += concat(marker, " tissuemesh tissue ", label, " ", name, "\n");
    return out;
}

} // namespace tissuemesh::io::detail

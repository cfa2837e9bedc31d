// A writer's output buffer that goes to the stream every megabyte, so that a format writer never holds
// its whole file (a 6.5 M-triangle head is 186 MB as PLY, several hundred MB as ascii).
#pragma once

#include <cstddef>
#include <ostream>
#include <string>

namespace tissuemesh::io::detail {

class ChunkedOutput {
public:
    explicit ChunkedOutput(std::ostream& out) : out_(out) {}

    /// Append here; call flush_if_full() after each record and flush() at the end.
    std::string text;

    void flush_if_full()
    {
        if (text.size() >= chunk) flush();
    }
    void flush()
    {
        out_.write(text.data(), static_cast<std::streamsize>(text.size()));
        text.clear();
    }

private:
    static constexpr std::size_t chunk = std::size_t{1} << 20;
    std::ostream& out_;
};

} // namespace tissuemesh::io::detail

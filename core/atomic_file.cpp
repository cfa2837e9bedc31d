#include "core/atomic_file.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <fstream>
#include <sstream>
#include <system_error>
#include <unistd.h>

#include "core/error.h"

namespace tissuemesh {
namespace fs = std::filesystem;

namespace {

fs::path temporary_name(const fs::path& path)
{
    static std::atomic<unsigned> counter{0};
    const std::string prefix = concat(".tmp-", ::getpid(), "-", counter++, "-");
    return path.parent_path() / (prefix + path.filename().string());
}

} // namespace

void write_atomically(const fs::path& path, const std::function<void(const fs::path&)>& write)
{
    const fs::path directory = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    std::error_code ec;
    if (!fs::is_directory(directory, ec))
        throw IoError(concat(path.string(), ": cannot write, the directory ", directory.string(),
                             " does not exist; create it first"));
    if (fs::is_directory(path, ec))
        throw IoError(concat(path.string(), ": cannot write, it is a directory; give a file name"));
    const fs::path temporary = temporary_name(path);
    try {
        write(temporary);
    } catch (...) {
        fs::remove(temporary, ec);
        throw;
    }
    fs::rename(temporary, path, ec);
    if (ec) {
        fs::remove(temporary, ec);
        throw IoError(concat(path.string(), ": cannot write (", ec.message(), "); check the permissions"));
    }
}

void write_stream_atomically(const fs::path& path, const std::function<void(std::ostream&)>& write)
{
    write_atomically(path, [&](const fs::path& temporary) {
        std::ofstream out(temporary, std::ios::binary);
        if (!out) throw IoError(concat(path.string(), ": cannot open for writing; check the permissions"));
        write(out);
        out.close();
        if (!out) throw IoError(concat(path.string(), ": write failed (disk full?)"));
    });
}

void write_text_atomically(const fs::path& path, const std::string& text)
{
    write_stream_atomically(path, [&](std::ostream& out) { out << text; });
}

std::string read_file_bytes(const fs::path& path)
{
    require_readable_file(path);
    std::ifstream in(path, std::ios::binary);
    std::ostringstream content;
    content << in.rdbuf();
    if (!in.good() && !in.eof()) throw IoError(concat(path.string(), ": read failed; check the file and the disk"));
    return content.str();
}

void require_readable_file(const fs::path& path)
{
    std::error_code ec;
    if (!fs::exists(path, ec)) throw IoError(concat(path.string(), ": no such file; check the path"));
    if (fs::is_directory(path, ec))
        throw IoError(concat(path.string(), ": is a directory, not a file; give the file inside it"));
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(concat(path.string(), ": cannot be opened for reading; check the permissions"));
}

std::string full_extension(const fs::path& path)
{
    std::string name = path.filename().string();
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
    for (const char* compressed : {".gz", ".bz2", ".xz"}) {
        const std::string suffix = compressed;
        if (name.size() > suffix.size() && name.ends_with(suffix)) {
            const std::string stem = name.substr(0, name.size() - suffix.size());
            const auto dot = stem.rfind('.');
            return dot == std::string::npos ? suffix : stem.substr(dot) + suffix;
        }
    }
    if (name.ends_with(".seg.nrrd")) return ".seg.nrrd";
    const auto dot = name.rfind('.');
    return dot == std::string::npos || dot == 0 ? std::string() : name.substr(dot);
}

} // namespace tissuemesh

#include "io/write_surface_streamed.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/detail/ply_format.h"

namespace tissuemesh::io {
namespace {

namespace fs = std::filesystem;

/// A file descriptor closed on destruction.
struct Descriptor {
    int fd;
    explicit Descriptor(int descriptor) : fd(descriptor) {}
    ~Descriptor()
    {
        if (fd >= 0) ::close(fd);
    }
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
};

/// A side file of records, appended to piece by piece and removed when the writer goes.
class SideFile {
public:
    SideFile(fs::path path, const fs::path& what) : path_(std::move(path)), what_(what), out_(path_, std::ios::binary)
    {
        if (!out_)
            throw IoError(
                concat(what_.string(), ": cannot open ", path_.string(), " for writing; check the permissions"));
    }
    ~SideFile()
    {
        std::error_code ec;
        fs::remove(path_, ec);
    }
    SideFile(const SideFile&) = delete;
    SideFile& operator=(const SideFile&) = delete;

    void write(const std::string& bytes)
    {
        out_.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        if (!out_) throw IoError(concat(what_.string(), ": write failed (disk full?)"));
    }

    /// Appends the whole side file to the file `target`, from byte `offset` on; returns the new end.
    std::size_t copy_to(const fs::path& target, std::size_t offset)
    {
        out_.close();
        if (!out_) throw IoError(concat(what_.string(), ": write failed (disk full?)"));
        const Descriptor in(::open(path_.c_str(), O_RDONLY)), out(::open(target.c_str(), O_WRONLY));
        if (in.fd < 0 || out.fd < 0)
            throw IoError(concat(what_.string(), ": cannot reopen ", path_.string(), " or the output"));
        // In the kernel where the file system allows it (no copy through user memory), else read and write.
        auto at = static_cast<off_t>(offset);
        while (true) {
            const ssize_t n = ::copy_file_range(in.fd, nullptr, out.fd, &at, std::size_t{1} << 30, 0);
            if (n == 0) return static_cast<std::size_t>(at);
            if (n > 0) continue;
            if (errno != EXDEV && errno != ENOSYS && errno != EINVAL && errno != EOPNOTSUPP)
                throw IoError(
                    concat(what_.string(), ": copying ", path_.string(), " failed (", std::strerror(errno), ")"));
            break;
        }
        std::vector<char> buffer(std::size_t{1} << 22);
        while (true) {
            const ssize_t n = ::pread(in.fd, buffer.data(), buffer.size(), at - static_cast<off_t>(offset));
            if (n == 0) return static_cast<std::size_t>(at);
            if (n < 0 || ::pwrite(out.fd, buffer.data(), static_cast<std::size_t>(n), at) != n)
                throw IoError(concat(what_.string(), ": copying ", path_.string(), " failed (disk full?)"));
            at += n;
        }
    }

private:
    fs::path path_;
    fs::path what_;
    std::ofstream out_;
};

/// The sink `produce` is given: checks each piece and appends its records to the two side files.
class PlySideWriter final : public InterfaceSink {
public:
    PlySideWriter(const fs::path& temporary, const fs::path& what)
        : what_(what), vertices_(fs::path(temporary.string() + ".vertices"), what),
          faces_(fs::path(temporary.string() + ".faces"), what)
    {
    }

    void start(const TissueNames& names, Label background) override
    {
        names_ = names;
        background_ = background;
    }

    void add(const InterfacePiece& piece) override
    {
        if (piece.first_vertex != vertex_count_ || piece.sides.size() != piece.triangles.size())
            throw InputError(concat(what_.string(), ": a streamed piece starts at vertex ", piece.first_vertex,
                                    " after ", vertex_count_, " vertices or has ", piece.sides.size(),
                                    " label pairs for ", piece.triangles.size(), " triangles; the producer is broken"));
        bytes_.clear();
        for (const Vec3& v : piece.vertices) {
            if (!is_finite(v))
                throw InputError(concat(what_.string(), ": vertex ",
                                        vertex_count_ + static_cast<std::size_t>(&v - piece.vertices.data()),
                                        " has a non-finite coordinate"));
            detail::append_ply_vertex(bytes_, v);
        }
        vertex_count_ += piece.vertices.size();
        vertices_.write(bytes_);
        bytes_.clear();
        for (std::size_t t = 0; t < piece.triangles.size(); ++t) {
            for (const std::uint32_t v : piece.triangles[t])
                if (v >= vertex_count_)
                    throw InputError(concat(what_.string(), ": triangle ", triangle_count_ + t, " refers to vertex ", v,
                                            " but only ", vertex_count_, " vertices came before it"));
            if (piece.sides[t].from == piece.sides[t].to)
                throw InputError(concat(what_.string(), ": triangle ", triangle_count_ + t, " separates tissue ",
                                        piece.sides[t].from, " from itself"));
            detail::append_ply_face(bytes_, piece.triangles[t], piece.sides[t]);
        }
        triangle_count_ += piece.triangles.size();
        faces_.write(bytes_);
    }

    /// Writes the PLY file `temporary`: header, then the vertex and face records.
    void finish(const fs::path& temporary)
    {
        const std::string header = detail::ply_header(names_, background_, vertex_count_, triangle_count_);
        {
            std::ofstream out(temporary, std::ios::binary);
            out << header;
            out.close();
            if (!out) throw IoError(concat(what_.string(), ": cannot write; check the permissions and the disk"));
        }
        faces_.copy_to(temporary, vertices_.copy_to(temporary, header.size()));
    }

private:
    fs::path what_;
    SideFile vertices_, faces_;
    TissueNames names_;
    Label background_ = 0;
    std::size_t vertex_count_ = 0, triangle_count_ = 0;
    std::string bytes_;
};

} // namespace

void write_surface_streamed(const fs::path& path, const std::function<void(InterfaceSink& sink)>& produce)
{
    if (full_extension(path) != ".ply")
        throw IoError(concat(path.string(), ": streamed writing supports .ply only; write other formats with "
                                            "write_surface()"));
    write_atomically(path, [&](const fs::path& temporary) {
        PlySideWriter writer(temporary, path);
        produce(writer);
        writer.finish(temporary);
    });
}

} // namespace tissuemesh::io

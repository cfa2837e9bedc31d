#include "io/surface_io.h"

#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/detail/obj_format.h"
#include "io/detail/off_format.h"
#include "io/detail/ply_format.h"
#include "io/detail/stl_format.h"
#include "io/detail/vtp_format.h"

namespace tissuemesh::io {
namespace {

const char* const known_extensions = ".ply, .vtp, .off, .stl, .obj";

std::string extension_of(const std::filesystem::path& path)
{
    const std::string extension = full_extension(path);
    if (extension != ".ply" && extension != ".vtp" && extension != ".off" && extension != ".stl" && extension != ".obj")
        throw IoError(
            concat(path.string(), ": unknown surface extension '", extension, "'; use one of ", known_extensions));
    return extension;
}

} // namespace

void write_surface(const InterfaceComplex& complex, const std::filesystem::path& path,
                   const std::vector<std::string>& ply_comments)
{
    write_surface(complex, path, SurfaceWriteOptions{.ascii = false, .ply_comments = ply_comments});
}

void write_surface(const InterfaceComplex& complex, const std::filesystem::path& path,
                   const SurfaceWriteOptions& options)
{
    for (const std::string& comment : options.ply_comments)
        if (comment.find_first_of("\r\n") != std::string::npos)
            throw IoError(concat(path.string(), ": a PLY comment cannot span lines"));
    const std::string extension = extension_of(path);
    validate_indices(complex, path.string());
    // Every format goes to the temporary file in chunks of about 1 MB, never whole in memory.
    write_stream_atomically(path, [&](std::ostream& out) {
        if (extension == ".ply") detail::write_ply(complex, out, options.ply_comments, options.ascii);
        if (extension == ".vtp") detail::write_vtp(complex, out);
        if (extension == ".off") detail::write_off(complex, out);
        if (extension == ".stl") detail::write_stl(complex, out, options.ascii);
        if (extension == ".obj") detail::write_obj(complex, out);
    });
}

InterfaceComplex read_surface(const std::filesystem::path& path)
{
    const std::string extension = extension_of(path);
    const std::string bytes = read_file_bytes(path);
    const std::string what = path.string();
    InterfaceComplex complex;
    if (extension == ".ply") complex = detail::parse_ply(bytes, what);
    if (extension == ".vtp") complex = detail::parse_vtp(bytes, what);
    if (extension == ".off") complex = detail::parse_off(bytes, what);
    if (extension == ".stl") complex = detail::parse_stl(bytes, what);
    if (extension == ".obj") complex = detail::parse_obj(bytes, what);
    validate_indices(complex, what);
    return complex;
}

} // namespace tissuemesh::io

#include "io/tet_mesh_io.h"

#include <fstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/detail/abaqus_format.h"
#include "io/detail/byte_reader.h"
#include "io/detail/medit_format.h"
#include "io/detail/msh2_format.h"
#include "io/detail/msh4_format.h"
#include "io/detail/msh_layouts.h"
#include "io/detail/tetgen_format.h"
#include "io/read_vtu.h"
#include "io/write_vtu.h"

namespace tissuemesh::io {
namespace fs = std::filesystem;
namespace {

const char* const known = ".msh, .mesh, .vtu, .node/.ele, .inp";

TetMesh read_msh(const fs::path& path)
{
    const std::string bytes = read_file_bytes(path);
    detail::ByteReader in(bytes, path.string());
    if (in.word() != "$MeshFormat") in.fail("not a Gmsh file (no $MeshFormat)", "check the file or its extension");
    const std::string version(in.next_word("a format version"));
    if (version.rfind("2.", 0) == 0) return detail::parse_msh2(in);
    if (version.rfind("4.", 0) == 0 && version != "4" && version != "4.0") return detail::parse_msh4(in);
    in.fail(concat("Gmsh format ", version, " is not supported"), "save as 2.2 or 4.1 (gmsh -format msh22 or msh41)");
}

fs::path with_extension(const fs::path& path, const char* extension)
{
    fs::path result = path;
    return result.replace_extension(extension);
}

} // namespace

bool is_tet_mesh_path(const fs::path& path)
{
    const std::string e = full_extension(path);
    return e == ".msh" || e == ".mesh" || e == ".vtu" || e == ".node" || e == ".ele" || e == ".inp";
}

namespace {

/// A .msh in SimNIBS's or DUNEuro's numbering.
void write_foreign_msh(const TetMesh& mesh, const fs::path& path, const TetMeshWriteOptions& options)
{
    if (options.numbering == TissueNumbering::simnibs) {
        const std::map<Label, int> tags = simnibs_tags(mesh, options.simnibs_table);
        write_text_atomically(path, detail::format_msh2(mesh.vertices, detail::simnibs_elements(mesh, tags), true));
        return;
    }
    if (options.duneuro_tag_offset < 0)
        throw InputError(concat("DUNEuro tag offset ", options.duneuro_tag_offset, " is negative; use 0 or more"));
    // The conductivities first: the mesh never names tissues that have none.
    const std::string conductivities = detail::duneuro_conductivity_file(mesh, options.duneuro_conductivities_s_per_m);
    write_text_atomically(with_extension(path, ".con"), conductivities);
    write_text_atomically(
        path, detail::format_msh2(mesh.vertices, detail::duneuro_elements(mesh, options.duneuro_tag_offset), false));
}

} // namespace

void write_tet_mesh(const TetMesh& mesh, const fs::path& path, const TetMeshWriteOptions& options)
{
    const std::string extension = full_extension(path);
    if (!is_tet_mesh_path(path))
        throw IoError(concat(path.string(), ": unknown mesh format \"", extension, "\"; use one of ", known));
    if (options.numbering != TissueNumbering::labels) {
        if (extension != ".msh")
            throw InputError(concat(path.string(), ": ",
                                    options.numbering == TissueNumbering::simnibs ? "SimNIBS" : "DUNEuro",
                                    " numbering is for Gmsh files; write a .msh"));
        validate_indices(mesh, path.string());
        return write_foreign_msh(mesh, path, options);
    }
    // write_vtu() validates the mesh itself.
    if (extension == ".vtu")
        return write_vtu(mesh, path, {}, {}, options.vtu_compressed ? VtuEncoding::compressed : VtuEncoding::ascii);
    validate_indices(mesh, path.string());
    if (extension == ".node" || extension == ".ele") {
        const detail::TetgenFiles files = detail::format_tetgen(mesh);
        write_text_atomically(with_extension(path, ".node"), files.node);
        write_text_atomically(with_extension(path, ".ele"), files.ele);
        write_text_atomically(with_extension(path, ".face"), files.face);
        return;
    }
    if (extension == ".msh")
        write_text_atomically(path, options.msh_version == MshVersion::v4_1
                                        ? detail::format_msh4(mesh, options.binary)
                                        : detail::format_msh2(mesh, options.binary));
    if (extension == ".mesh") write_text_atomically(path, detail::format_medit(mesh));
    if (extension == ".inp") write_text_atomically(path, detail::format_abaqus(mesh, path.string()));
}

TetMesh read_tet_mesh(const fs::path& path)
{
    const std::string extension = full_extension(path);
    TetMesh mesh;
    if (extension == ".msh") {
        mesh = read_msh(path);
    } else if (extension == ".mesh") {
        mesh = detail::parse_medit(read_file_bytes(path), path.string());
    } else if (extension == ".inp") {
        mesh = detail::parse_abaqus(read_file_bytes(path), path.string());
    } else if (extension == ".node" || extension == ".ele") {
        detail::TetgenFiles files;
        files.node = read_file_bytes(with_extension(path, ".node"));
        files.ele = read_file_bytes(with_extension(path, ".ele"));
        if (fs::exists(with_extension(path, ".face"))) files.face = read_file_bytes(with_extension(path, ".face"));
        mesh = detail::parse_tetgen(files, with_extension(path, "").string());
    } else if (extension == ".vtu") {
        mesh = read_vtu(path).mesh;
    } else {
        throw IoError(concat(path.string(), ": cannot read meshes of type \"", extension, "\"; use one of ", known));
    }
    validate_indices(mesh, path.string());
    return mesh;
}

} // namespace tissuemesh::io

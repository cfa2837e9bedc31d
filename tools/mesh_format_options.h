// The --msh-version / --binary / --vtu-ascii flags of every tool that writes a tet mesh.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "core/error.h"
#include "io/tet_mesh_io.h"

namespace tissuemesh::tools {

/// What the flags hold until to_write_options() turns them into the io options.
struct MeshFormatFlags {
    std::string msh_version = "2.2";
    bool binary = false;
    bool vtu_ascii = false;

    void add_to(CLI::App& app)
    {
        app.add_option("--msh-version", msh_version, ".msh output: 2.2 (SimNIBS, DUNEuro) or 4.1")
            ->check(CLI::IsMember({"2.2", "4.1"}))
            ->capture_default_str();
        app.add_flag("--binary", binary, ".msh output in binary instead of ASCII");
        app.add_flag("--vtu-ascii", vtu_ascii, ".vtu output as ASCII instead of zlib-compressed binary");
    }

    /// @throws InputError for a version other than 2.2 or 4.1
    io::TetMeshWriteOptions to_write_options() const
    {
        if (msh_version != "2.2" && msh_version != "4.1")
            throw InputError(concat("--msh-version ", msh_version, " is not supported; use 2.2 or 4.1"));
        io::TetMeshWriteOptions options;
        options.msh_version = msh_version == "4.1" ? io::MshVersion::v4_1 : io::MshVersion::v2_2;
        options.binary = binary;
        options.vtu_compressed = !vtu_ascii;
        return options;
    }
};

} // namespace tissuemesh::tools

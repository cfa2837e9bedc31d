// The --msh-version / --binary / --vtu-ascii / --tissue-numbering flags of every tool that writes a tet mesh.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "core/error.h"
#include "fem/conductivities.h"
#include "io/read_conductivity_table.h"
#include "io/simnibs_tags.h"
#include "io/tet_mesh_io.h"
#include "tools/run_tool.h"

namespace tissuemesh::tools {

/// What the flags hold until to_write_options() turns them into the io options.
struct MeshFormatFlags {
    std::string msh_version = "2.2";
    bool binary = false;
    bool vtu_ascii = false;
    std::string numbering = "labels";
    std::string tissue_tags;  ///< --tissue-tags FILE (simnibs)
    std::string conductivity; ///< --conductivity FILE (duneuro)
    int duneuro_offset = 1;

    void add_to(CLI::App& app)
    {
        app.add_option("--msh-version", msh_version, ".msh output: 2.2 (SimNIBS, DUNEuro) or 4.1")
            ->check(CLI::IsMember({"2.2", "4.1"}))
            ->capture_default_str();
        app.add_flag("--binary", binary, ".msh output in binary instead of ASCII");
        app.add_flag("--vtu-ascii", vtu_ascii, ".vtu output as ASCII instead of zlib-compressed binary");
        app.add_option(
               "--tissue-numbering", numbering,
               ".msh tags: labels (ours), simnibs (SimNIBS's tissue numbers from the names, 2.2 binary; "
               "FieldTrip/Brainstorm read them too) or duneuro (2.2 ASCII dune-grid reads, tets only, tags from "
               "--duneuro-offset, conductivities in <stem>.con beside)")
            ->check(CLI::IsMember({"labels", "simnibs", "duneuro"}))
            ->capture_default_str();
        app.add_option("--tissue-tags", tissue_tags,
                       "simnibs: JSON of SimNIBS tags for tissues it has no name for "
                       "({\"air cavities\": 13})")
            ->type_name("FILE");
        app.add_option("--conductivity", conductivity,
                       "duneuro: conductivity table (S/m, tm-solve's format; head "
                       "defaults by name)")
            ->type_name("FILE");
        app.add_option("--duneuro-offset", duneuro_offset,
                       "duneuro: tag of the first tissue (DUNEuro's tensors.offset)")
            ->check(CLI::NonNegativeNumber)
            ->capture_default_str();
    }

    /// Checks that the flags fit together (before a long step: the tables are read only at the end).
    /// @throws InputError naming the flag and the fix
    void check() const
    {
        if (msh_version != "2.2" && msh_version != "4.1")
            throw InputError(concat("--msh-version ", msh_version, " is not supported; use 2.2 or 4.1"));
        if (!tissue_tags.empty() && numbering != "simnibs")
            throw InputError("--tissue-tags maps tissues to SimNIBS tags; add --tissue-numbering simnibs");
        if (!conductivity.empty() && numbering != "duneuro")
            throw InputError("--conductivity gives DUNEuro its conductivity file; add --tissue-numbering duneuro");
        if (numbering != "labels" && msh_version == "4.1")
            throw InputError(concat("--tissue-numbering ", numbering, " writes Gmsh 2.2, as ",
                                    numbering == "simnibs" ? "SimNIBS" : "DUNEuro",
                                    " reads it; drop --msh-version 4.1"));
        if (numbering == "duneuro" && binary)
            throw InputError("--tissue-numbering duneuro writes ASCII (dune-grid reads no binary .msh); drop --binary");
    }

    /// The io options for writing `mesh`: its conductivities resolved for DUNEuro (scalars only).
    /// @throws InputError for flags that do not fit together (check()), an anisotropic conductivity for DUNEuro, or
    ///         a bad table
    io::TetMeshWriteOptions to_write_options(const TetMesh& mesh = {}) const
    {
        check();
        io::TetMeshWriteOptions options;
        options.msh_version = msh_version == "4.1" ? io::MshVersion::v4_1 : io::MshVersion::v2_2;
        options.binary = binary;
        options.vtu_compressed = !vtu_ascii;
        if (numbering == "simnibs") {
            options.numbering = io::TissueNumbering::simnibs;
            if (!tissue_tags.empty()) options.simnibs_table = io::read_simnibs_tag_table(tissue_tags);
        }
        if (numbering == "duneuro") {
            options.numbering = io::TissueNumbering::duneuro;
            options.duneuro_tag_offset = duneuro_offset;
            const fem::ConductivityTable table =
                conductivity.empty() ? fem::ConductivityTable{} : io::read_conductivity_table(conductivity);
            const fem::Conductivities resolved =
                with_source(conductivity.empty() ? "the default conductivities" : conductivity,
                            [&] { return fem::resolve_conductivities(mesh, table); });
            for (const auto& [label, tensor] : resolved.by_label) {
                if (tensor != fem::isotropic(tensor[0]))
                    throw InputError(concat(conductivity, ": tissue ", label,
                                            " has an anisotropic conductivity; DUNEuro's "
                                            "conductivity file holds one number per tissue"));
                options.duneuro_conductivities_s_per_m[label] = tensor[0];
            }
        }
        return options;
    }
};

} // namespace tissuemesh::tools

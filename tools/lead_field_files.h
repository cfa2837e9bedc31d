// The files of tm-leadfield, which tm-solve reads back: a NumPy .npy matrix and a JSON sidecar next to it
// (same name, .json) saying what its rows and columns are, for which mesh and conductivities.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/tet_mesh.h"
#include "fem/conductivities.h"
#include "fem/tdcs_lead_field.h"
#include "io/npy.h"

namespace tissuemesh::tools {

/// "eeg.npy" -> "eeg.json" (any other name gets ".json" appended).
std::filesystem::path sidecar_path(const std::filesystem::path& npy);

/// A hash of the mesh's nodes, tets and tissues (64-bit FNV-1a, 16 hex digits): a lead field belongs to the
/// mesh it was computed on, and renumbering or moving one node changes it.
std::string mesh_fingerprint(const TetMesh& mesh);

/// The sidecar's "mesh": its path as given, node and tet counts, fingerprint.
nlohmann::json mesh_description(const std::string& path, const TetMesh& mesh);

/// The sidecar's "conductivities": S/m by tissue name (label when unnamed), a number when isotropic, else 9.
nlohmann::json conductivity_description(const TetMesh& mesh, const fem::Conductivities& conductivities);

/// Writes the rows x columns matrix `values` (C order) to `npy` and `sidecar` next to it, both or neither.
/// @throws IoError when either cannot be written
void write_lead_field(const std::filesystem::path& npy, std::size_t rows, std::size_t columns, const double* values,
                      const nlohmann::json& sidecar);

/// A tDCS lead field read back, with its electrodes (input order, the reference included).
struct TdcsLeadFieldFile {
    fem::TdcsLeadField lead_field;
    std::vector<std::string> names;
    std::vector<Vec3> centres_mm;
    std::vector<double> radii_mm;
};

/// Reads a tDCS lead field that tm-leadfield wrote for `mesh`.
/// @throws IoError when the .npy or its sidecar is missing, unreadable or not a tDCS lead field
/// @throws InputError when it was computed for another mesh (node count or fingerprint)
TdcsLeadFieldFile read_tdcs_lead_field(const std::filesystem::path& npy, const TetMesh& mesh);

} // namespace tissuemesh::tools

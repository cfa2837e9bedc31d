// The real clients the format tests talk to: Debian's python3-meshio and the gmsh program. Both are
// installed by scripts/setup, so a missing one is a test failure, not a skip.
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/tet_mesh.h"

namespace tissuemesh::testing {

/// What meshio sees in a file: point count, cells per type, and per tet label (from gmsh:physical,
/// medit:ref, tetgen:ref, "tissue" cell data, or, for Abaqus, the number a cell set's name ends with)
/// the tet count and total unsigned volume. Fails the test (ADD_FAILURE) when meshio is missing or the
/// read fails.
struct MeshioView {
    bool ok = false;
    std::size_t points = 0;
    std::map<std::string, std::size_t> cells; ///< "tetra", "triangle", ...
    std::map<Label, std::size_t> tets_per_label;
    std::map<Label, double> volume_per_label; ///< mm^3
    std::vector<std::string> cell_sets;       ///< Abaqus element sets, $PhysicalNames, ...
    std::string error;
};
MeshioView meshio_read(const std::filesystem::path& file);

/// Writes the two-cube mesh below with meshio in `format` ("gmsh22", "gmsh", "medit", "tetgen",
/// "abaqus", "vtu" (base64, zlib), "vtu-raw" (base64), "vtu-lzma", "vtu-ascii"; the .vtu ones with cell
/// data "tissue" and "volume" (1/6 each), point data "phi" = x + 2 y); returns false (with ADD_FAILURE)
/// when meshio fails.
/// The mesh: two unit cubes side by side, 6 Kuhn tets each: tissue 1 at x in [0, 1], tissue 2 at [1, 2],
/// 12 points.
bool meshio_write_two_cubes(const std::filesystem::path& file, const std::string& format, bool binary);

/// The labelled mesh every client test writes (testing::nested_cubes_mesh(), built once).
const TetMesh& client_sample();
/// Tets per tissue label.
std::map<Label, std::size_t> tets_per_label(const TetMesh& mesh);

/// Runs gmsh with `args` in `working_dir`; fails the test when gmsh is missing or exits non-zero.
bool run_gmsh(const std::vector<std::string>& args, const std::filesystem::path& working_dir);

} // namespace tissuemesh::testing

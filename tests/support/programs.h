// Test helpers: running other programs (python3, gmsh) and the labelled tet meshes the format tests share.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/tet_mesh.h"
#include "tests/support/cli.h"

namespace tissuemesh::testing {

/// Runs `program` (an absolute path, or a name looked up on PATH) with `args`, standard input from
/// /dev/null, in `working_dir` when given; returns the exit code (127: not found) and output.
CliResult run_program(const std::string& program, const std::vector<std::string>& args,
                      const std::filesystem::path& working_dir = {});

/// A 4 x 4 x 4 mm block (tissue 1, "outer") holding a 2 x 2 x 2 mm cube (tissue 2, "inner") at (1, 1, 1),
/// tetrahedralized with every interface kept: exact volumes 56 and 8 mm^3, faces {2, 1} and {1, 0}.
TetMesh nested_cubes_mesh();

/// Sum of the tet volumes of each tissue (mm^3).
std::map<Label, double> tissue_volumes(const TetMesh& mesh);

} // namespace tissuemesh::testing

// Test helpers: the labelled tet meshes the format tests share (run other programs with run_program, cli.h).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/tet_mesh.h"
#include "tests/support/cli.h"

namespace tissuemesh::testing {

/// A 4 x 4 x 4 mm block (tissue 1, "outer") holding a 2 x 2 x 2 mm cube (tissue 2, "inner") at (1, 1, 1),
/// tetrahedralized with every interface kept: exact volumes 56 and 8 mm^3, faces {2, 1} and {1, 0}.
TetMesh nested_cubes_mesh();

/// Sum of the tet volumes of each tissue (mm^3).
std::map<Label, double> tissue_volumes(const TetMesh& mesh);

} // namespace tissuemesh::testing

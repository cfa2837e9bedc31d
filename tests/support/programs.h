// Test helpers: the labelled tet meshes the format tests share (run other programs with run_program, cli.h).
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/label_image.h"
#include "core/tet_mesh.h"
#include "tests/support/cli.h"

namespace tissuemesh::testing {

/// A 4 x 4 x 4 mm block (tissue 1, "outer") holding a 2 x 2 x 2 mm cube (tissue 2, "inner") at (1, 1, 1),
/// tetrahedralized with every interface kept: exact volumes 56 and 8 mm^3, faces {2, 1} and {1, 0}. Built once.
const TetMesh& nested_cubes_mesh();

/// A phantom's image and its tet mesh through tm-extract's and tm-tetra's steps (extract_interfaces, then
/// tetrahedralize with the default options).
struct MeshedPhantom {
    LabelImage image;
    TetMesh mesh;
};
/// The phantom `name` (image::make_phantom) at `voxel_mm`, meshed once per name and size for the whole run.
const MeshedPhantom& meshed_phantom(const std::string& name, double voxel_mm);

/// Swaps two corners of every tet of negative volume, so that every tet is positively oriented.
void orient_positively(TetMesh& mesh);

/// One tet of `tissue` with these corners, positively oriented.
TetMesh single_tet(const std::array<Vec3, 4>& corners, Label tissue = 1);

/// The axis orders of kuhn_cube()'s tets: tet k holds the points x with x[order[0]] >= x[order[1]] >= x[order[2]].
inline constexpr std::array<std::array<int, 3>, 6> kuhn_axis_orders{
    {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};

/// The cube [0, s]^3 split into the 6 Kuhn tets around its main diagonal (kuhn_axis_orders), all of tissue 1,
/// positively oriented.
TetMesh kuhn_cube(double s);

/// Sum of the tet volumes of each tissue (mm^3).
std::map<Label, double> tissue_volumes(const TetMesh& mesh);

} // namespace tissuemesh::testing

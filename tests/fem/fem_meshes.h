// Meshes for the FEM tests, generated in code: structured boxes and concentric spherical shells.
#pragma once

#include <functional>
#include <vector>

#include "core/interface_complex.h"
#include "core/tet_mesh.h"
#include "fem/sphere_series.h"

namespace tissuemesh::testing {

/// [0, size]^3 mm cut into n^3 cubes of 6 tets each (Kuhn subdivision, positively oriented); interior
/// nodes moved by up to `jitter` times the cube edge (deterministic pseudo-random, < 0.25 keeps tets
/// valid). Tissue per tet from `label_of(centroid_mm)` (default: 1 everywhere).
TetMesh box_mesh(int n, double size_mm, double jitter = 0, const std::function<Label(const Vec3&)>& label_of = nullptr);

/// Icosahedron subdivided `levels` times, projected on the sphere; normals point outwards.
InterfaceComplex icosphere(int levels, double radius_mm);

/// Concentric shells around the origin with radii r[0] < r[1] < ...: the ball inside r[0] is left out
/// (a cavity), the shell between r[k] and r[k+1] is tissue k+1. Surfaces are icospheres of `levels`
/// (their vertices lie on the exact spheres; no Steiner point on them), tets bounded by `max_volume_mm3`.
TetMesh shell_mesh(const std::vector<double>& radii_mm, int levels, double max_volume_mm3);

/// The 4-shell sphere head of the spheres4 phantom built from icospheres: brain (4) inside 78 mm, csf (3)
/// to 80 mm, skull (2) to 86 mm, scalp (1) to 92 mm, centred at the origin.
TetMesh four_shell_head(int levels, double max_volume_mm3);

/// The same head as the analytic series (fem/sphere_series.h) sees it: brain, csf, skull, scalp at 0.33, 1.79,
/// 0.01 and 0.43 S/m (the default conductivities by name).
inline const fem::LayeredSphere four_shell_series{{78, 80, 86, 92}, {0.33, 1.79, 0.01, 0.43}};

/// A ball of tissue 1 ("brain") of radius `radius_mm` around the origin, its surface an icosphere.
TetMesh ball_mesh(double radius_mm, int levels, double max_volume_mm3);

} // namespace tissuemesh::testing

// Interface complexes built in code for the checker's tests: exact geometry, known volumes.
#pragma once

#include <vector>

#include "core/interface_complex.h"

namespace tissuemesh::testing {

/// Voxel labels on an nx by ny by nz grid (i fastest), the outside being `complex.background` (0).
struct VoxelBlock {
    std::size_t nx = 1, ny = 1, nz = 1;
    std::vector<Label> labels; ///< nx * ny * nz labels
    double size_mm = 1.0;      ///< edge length of a voxel
    Vec3 origin_mm{0, 0, 0};   ///< corner of voxel (0, 0, 0)
};

/// The faces between differently labelled voxels (and the outside) as an interface complex: each unit
/// square split into two triangles, vertices shared on the lattice, normals pointing from `from` to `to`.
/// Tissues are exact unions of cubes, so their volumes are known.
InterfaceComplex voxel_faces(const VoxelBlock& block);

/// A box [low, high] of tissue `inside` against `outside`, 8 new vertices, 12 outward triangles.
void add_box(InterfaceComplex& complex, const Vec3& low, const Vec3& high, Label inside, Label outside);

/// The tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1) scaled by `size_mm` and shifted by `offset_mm`,
/// of tissue `inside` against `outside`: 4 new vertices, 4 outward triangles.
void add_tetrahedron(InterfaceComplex& complex, const Vec3& offset_mm, double size_mm, Label inside, Label outside);

/// An icosahedron subdivided `levels` times (20 * 4^levels triangles), vertices on the sphere of
/// `radius_mm` around `centre_mm`; tissue 1 inside, background 0 outside.
InterfaceComplex icosphere(int levels, double radius_mm, const Vec3& centre_mm);

/// The complex with triangle `t`'s vertex order reversed (its normal flipped, labels kept).
void flip_triangle(InterfaceComplex& complex, std::size_t t);

/// Appends a lone triangle of pair {from, to}; returns its index.
std::uint32_t add_lone_triangle(InterfaceComplex& complex, const Vec3& a, const Vec3& b, const Vec3& c, LabelPair pair);

} // namespace tissuemesh::testing

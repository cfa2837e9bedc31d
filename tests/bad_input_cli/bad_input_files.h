// Bad input files for the catalogue: each written into a folder next to valid ones, so a case differs from
// a working run by exactly one defect.
#pragma once

#include <filesystem>

namespace tissuemesh::testing {

/// Writes into `dir` the valid files the cases start from and every bad variant the catalogue names:
///  - images: ok.nii (2x2x2, labels 1..7), one-label.nii (only background), one-voxel.nii (a single
///    tissue voxel), border.nii (tissue on the image border), NRRD/MetaImage variants;
///  - surfaces: ok.ply (a closed box of tissue 1), hole.ply, flipped.ply, duplicate.ply,
///    twin-vertices.ply, crossing.ply, nan.ply, dangling.ply, truncated.ply, empty.ply, magic.ply,
///    counts.off, truncated.stl;
///  - meshes: ok.msh (one tet, tissue 1 "brain"), flat.msh (a tet of zero volume), dangling.msh, nan.msh,
///    truncated.msh, no-tets.msh, bad.mesh; ok.vtu (the same tet), triangle.vtu, dangling.vtu, truncated.vtu;
///  - tables: conductivity, sensor, electrode montage and label files, valid and not.
void write_bad_input_files(const std::filesystem::path& dir);

} // namespace tissuemesh::testing

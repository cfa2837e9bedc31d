// The tet-mesh checker: conformity, interfaces, tissues, quality, and agreement with the voxels.
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "core/label_image.h"
#include "core/progress.h"
#include "core/tet_mesh.h"

namespace tissuemesh::volume {

struct TissueMeshStats {
    std::size_t tets = 0;
    double volume_mm3 = 0;
    std::size_t components = 0;   ///< face-connected pieces of this tissue's tets
    double voxel_volume_mm3 = -1; ///< with an image: the tissue's voxel volume, else -1
    double dice = -1;             ///< with an image: Dice of (voxel centres in this tissue's tets) vs voxels
};

struct QualityStats {
    double min_dihedral_deg = 0; ///< smallest dihedral angle over all tets
    double max_dihedral_deg = 0;
    double max_radius_edge_ratio = 0; ///< circumradius / shortest edge (regular tet: 0.612)
    double mean_radius_edge_ratio = 0;
    std::array<std::size_t, 18> min_dihedral_histogram{}; ///< tets by their smallest dihedral, 10 deg bins
    double p1_min_dihedral_deg = 0;                       ///< 1st percentile of the tets' smallest dihedral angles
};

struct MeshCheckReport {
    std::size_t nodes = 0, tets = 0, faces = 0;
    std::size_t inverted_tets = 0; ///< signed volume <= 0
    /// Positive volume under flat_volume_ratio times the cube of the longest edge: four (nearly) coplanar
    /// nodes. Such a tet's P1 gradients grow as 1/volume and its stiffness entries swamp the rest.
    std::size_t flat_tets = 0;
    std::size_t nonconforming_faces = 0; ///< faces shared by more than two tets
    std::size_t open_boundary_edges = 0; ///< edges of the outer boundary not matched by a reverse edge
    /// Pairs of outer-boundary faces that meet other than at the nodes and edges they share: the boundary passes
    /// through itself, and the tets behind the two faces overlap (no tet need be inverted for that).
    std::size_t boundary_crossings = 0;
    std::size_t unused_nodes = 0;
    std::size_t missing_interface_faces = 0;     ///< marked faces that are not tet faces
    std::size_t mislabelled_interface_faces = 0; ///< marked faces whose tets disagree with the face's tissues
    std::size_t unmarked_interfaces = 0;         ///< faces between tets of different tissues that are not marked
    std::map<Label, TissueMeshStats> tissues;
    QualityStats quality;
    std::vector<std::string> problems; ///< one line each, with a location in mm (capped)

    /// How many defects of the tets and their faces there are: inverted or flat tets, non-conforming faces, open
    /// or self-crossing outer boundary, missing, mislabelled or unmarked interface faces (unused nodes are not
    /// counted).
    std::size_t tet_defects() const
    {
        return inverted_tets + flat_tets + nonconforming_faces + open_boundary_edges + boundary_crossings +
               missing_interface_faces + mislabelled_interface_faces + unmarked_interfaces;
    }
    /// True when the mesh is fit for FEM: conforming, no inverted tets, a closed boundary that does not cross
    /// itself, interfaces right.
    bool ok() const { return tet_defects() == 0 && unused_nodes == 0; }
};

/// Volume over the cube of the longest edge below which a tet counts as flat. A regular tet has
/// 1 / (6 sqrt 2) = 0.118; slivers of a few tenths of a degree, bad as they are, stay above 1e-5.
inline constexpr double flat_volume_ratio = 1e-9;

/// Checks `mesh`; with a non-empty `image`, also each tissue's voxel agreement (Dice), by rasterize_tets().
MeshCheckReport check_mesh(const TetMesh& mesh, const LabelImage* image = nullptr, const Progress& progress = {});

} // namespace tissuemesh::volume

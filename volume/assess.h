// Element assessment (Mueller & Sachse): each tet measured against the voxels it covers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

#include "core/label_image.h"
#include "core/progress.h"
#include "core/tet_mesh.h"

namespace tissuemesh::volume {

/// Options for assess_elements(). Volumes in mm^3, weights without unit.
struct AssessOptions {
    std::map<Label, double> priority; ///< weight per tissue for the majority vote (absent: 1; must be > 0)
    double error_weight = 1.0;        ///< quality key weight of the error volume, counted in voxels
    double shape_weight = 0.1;        ///< quality key weight of the shape term (radius-edge ratio, 0 if regular)
    Label background = 0;             ///< tissue outside the image, for sub-voxel samples near its border
    /// The priority tm-extract was given (--priority), so that sub-voxel samples see the tissues its split
    /// cubes put there (empty: the plain Kuhn rule, as extract_interfaces() without a priority)
    std::map<Label, int> extract_priority;
};

/// One bin of a tet's tissue histogram.
struct LabelCount {
    Label label = 0;
    std::uint32_t count = 0;
};

/// Per-tissue agreement between the mesh (tets by their current label) and the image.
struct TissueAssessment {
    std::size_t image_voxels = 0;    ///< voxels of this tissue in the whole image
    std::size_t mesh_voxels = 0;     ///< voxel centres inside tets of this tissue
    std::size_t agreeing_voxels = 0; ///< voxel centres of this tissue inside tets of this tissue
    double dice = 1.0;               ///< 2 agreeing / (image + mesh); 1 when both are 0
    double mesh_volume_mm3 = 0;      ///< sum of the volumes of this tissue's tets
    double voxel_volume_mm3 = 0;     ///< image_voxels x voxel volume
    double volume_error_mm3 = 0;     ///< mesh_volume_mm3 - voxel_volume_mm3
    double error_volume_mm3 = 0;     ///< voxel centres in this tissue's tets that are not of it, x voxel volume
};

/// The assessment of every tet (arrays of #T entries, indexed like mesh.tets) and of the whole mesh.
///
/// Histogram: for a tet holding voxel centres (voxel_count[t] > 0), the number of centres per tissue;
/// for a tet holding none (sampled[t] == 1), the tissues of its 5 sub-voxel samples (see assess_elements).
/// Stored as CSR: tet t's bins are histogram[histogram_offsets[t] .. histogram_offsets[t + 1]), labels
/// ascending.
struct Assessment {
    std::vector<std::size_t> histogram_offsets;    ///< #T + 1
    std::vector<LabelCount> histogram;             ///< all tets' bins, back to back
    std::vector<std::uint32_t> voxel_count;        ///< #T voxel centres held (rasterize_tets' ownership)
    std::vector<std::uint8_t> sampled;             ///< #T 1 when the tet holds no centre and was sampled
    std::vector<Label> majority;                   ///< #T argmax of priority x count (ties: see assess_elements)
    std::vector<double> error_volume_mm3;          ///< #T volume not of the tet's current tissue
    std::vector<double> majority_error_volume_mm3; ///< #T volume not of the majority tissue
    std::vector<double> volume_mm3;                ///< #T signed volume
    std::vector<double> min_dihedral_deg;          ///< #T smallest dihedral angle
    std::vector<double> radius_edge_ratio;         ///< #T circumradius / shortest edge (regular: sqrt(6)/4)
    std::vector<double> aspect_ratio;              ///< #T longest edge / (2 sqrt(6) inradius): 1 when regular
    std::vector<double> quality_key;               ///< #T larger = worse
    std::vector<std::uint32_t> worst_first;        ///< #T tet indices by quality key, descending (ties: index)

    std::map<Label, TissueAssessment> tissues;  ///< every label of the image or the mesh
    std::size_t voxels_inside = 0;              ///< voxel centres inside the mesh (== sum of voxel_count)
    std::size_t sampled_tets = 0;               ///< tets that hold no voxel centre
    double total_error_volume_mm3 = 0;          ///< centres not of their tet's tissue x voxel volume
    double total_majority_error_volume_mm3 = 0; ///< centres not of their tet's majority x voxel volume
    double sampled_error_volume_mm3 = 0;        ///< estimate of the sampled tets' error volume (not in the totals)
};

/// Assesses every tet of `mesh` against `image` (the paper's element assessment).
///
/// Voxels: rasterize_tets() gives each voxel centre to at most one tet (its tie rule); a counting sort of
/// that owner array gives each tet its centres, so the cost is linear in voxels + tets. A tet's error
/// volume is (centres it holds - centres of its tissue) x voxel volume, exactly; the totals sum these.
/// Majority: argmax over tissues of priority(tissue) x count. Ties go to the tet's current tissue when it
/// is among the tied ones (relabelling never changes a tet without reason), else to the smallest label.
/// Sub-voxel sampling: a tet holding no centre is sampled at its centroid and at the 4 points with
/// barycentric weight 0.7 on one vertex and 0.1 on the others. A sample's tissue is the one
/// extract_interfaces() (with `background` and `extract_priority`) puts there, by surface::ExtractedTissue:
/// the corners of the Kuhn tet (or of the priority rule's split-cube tet) holding the sample vote with their
/// barycentric weights, the largest sum wins. (Why not the nearest voxel: it disagrees with the surfaces
/// near their edges and corners; on the 2 mm spheres4 tm-tetra mesh it gave 255 k of 2.9 M tets another
/// majority than their tissue, this rule none.) A sampled tet's error volume is (samples not of its tissue
/// / 5) x its volume: an estimate, reported per tet and in sampled_error_volume_mm3, never in the totals.
/// Quality key (larger = worse):
///     key = error_weight x error_volume_mm3 / voxel volume + shape_weight x (radius_edge / (sqrt(6)/4) - 1)
/// i.e. misclassified voxels plus the shape's distance from the regular tet (radius-edge capped at 1e6).
/// Dice per tissue as check_mesh() computes it (same numbers, by current tet labels).
/// @pre  mesh tets positively oriented and conforming (rasterize_tets' precondition)
/// @throws InputError when the image is empty, an index is out of range or a priority is not > 0
Assessment assess_elements(const TetMesh& mesh, const LabelImage& image, const AssessOptions& options = {},
                           const Progress& progress = {});

/// The tissue of every tet set to its majority in `assessment` (the --relabel of tm-assess). Interface
/// faces are not touched: call mark_interfaces() afterwards.
void relabel_by_majority(TetMesh& mesh, const Assessment& assessment);

} // namespace tissuemesh::volume

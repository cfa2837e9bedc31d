// What a user needs to know about a label image before meshing it: per-tissue sizes, extents,
// connectivity, contacts, and the warnings (border, one-voxel-thin places, tiny islands).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/label_image.h"
#include "core/progress.h"

namespace tissuemesh::image {

/// Options of analyze_labels().
struct LabelStatisticsOptions {
    std::size_t island_voxels = 10; ///< 26-connected components under this many voxels are "tiny islands"
    Label background = 0;           ///< the surrounding label: no border, thin or island warnings for it
};

/// Statistics of one label.
struct LabelSummary {
    Label label = 0;
    std::string name; ///< image.name_of(label)
    std::size_t voxels = 0;
    double volume_mm3 = 0;                         ///< voxels * voxel volume
    std::array<std::size_t, 3> index_min{0, 0, 0}; ///< bounding box of its voxels (indices, inclusive)
    std::array<std::size_t, 3> index_max{0, 0, 0};
    std::array<Vec3, 2> bounds_mm{}; ///< world axis-aligned box of its voxel cells {min, max}
    std::size_t components6 = 0;     ///< connected components, face neighbours
    std::size_t components26 = 0;    ///< connected components, face/edge/corner neighbours
    std::vector<Label> touches;      ///< labels sharing a voxel face with it, ascending
    std::size_t border_voxels = 0;   ///< its voxels on the image border
    std::size_t thin_voxels = 0;   ///< voxels whose two opposite face neighbours along some axis are both other labels
    std::size_t islands = 0;       ///< 26-connected components under options.island_voxels
    std::size_t island_voxels = 0; ///< voxels in those islands
    std::vector<std::string> warnings; ///< one line each, with the fix
};

/// Statistics of a whole image.
struct LabelStatistics {
    Dims dims{0, 0, 0};
    Vec3 spacing_mm{0, 0, 0};
    Vec3 origin_mm{0, 0, 0};
    Mat3 direction = identity_matrix();
    std::string orientation;         ///< axis code such as "RAS" (see orientation_code())
    std::array<Vec3, 2> bounds_mm{}; ///< world box of the whole grid
    std::size_t voxel_count = 0;
    std::vector<LabelSummary> labels; ///< every label present, ascending
};

/// Analyses the image in linear time (a few passes over the voxels and two union-finds).
/// @pre  image is not empty
/// @throws InputError for an empty image or one of 2^32 voxels or more
LabelStatistics analyze_labels(const LabelImage& image, const LabelStatisticsOptions& options = {},
                               const Progress& progress = {});

/// The anatomical direction each voxel axis points to, as the RAS+ world defines it: "RAS" for the
/// identity (i -> Right, j -> Anterior, k -> Superior), "LPS" for its negation; the closest axis wins.
std::string orientation_code(const Mat3& direction);

} // namespace tissuemesh::image

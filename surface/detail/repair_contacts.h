// The geometric half of repair(): zero-area triangles collapsed away, and intersections and near-contacts
// between surfaces removed by local vertex moves through the editor (tolerant of the intersections that
// are already there, never adding one).
#pragma once

#include <cstddef>

#include "core/label_image.h"
#include "core/progress.h"
#include "surface/detail/complex_editor.h"
#include "surface/detail/repair_log.h"

namespace tissuemesh::surface::detail {

/// Collapses each triangle whose three distinct vertices are collinear along one of its edges (shortest
/// first), so that it and its neighbour across that edge disappear; counts and logs each.
/// @pre `editor` tolerates existing intersections
void collapse_degenerate_triangles(ComplexEditor& editor, RepairLog& log);

struct SeparateOptions {
    double gap_mm = 0;                 ///< near-contacts closer than this are pushed apart (0: none)
    std::size_t max_rounds = 30;       ///< rounds per phase (intersections, then near-contacts)
    const LabelImage* image = nullptr; ///< when given, moves keep vertices near their tissues' voxels
    double max_depth_voxels = 0.5;
};

/// Removes intersections, then near-contacts: the vertices of the triangles involved move apart along
/// their normals, each away from the tissue the two patches share (a patch crossing itself is smoothed
/// instead), in rounds, the region growing by a ring of neighbours when a round makes no progress.
/// Fills the report's contact counts, moved vertices and actions.
/// @throws AlgorithmError when intersections remain after the last round, naming the first
void separate_surfaces(ComplexEditor& editor, const SeparateOptions& options, RepairLog& log, const Progress& progress);

} // namespace tissuemesh::surface::detail

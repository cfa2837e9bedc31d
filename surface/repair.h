// Repair of an interface complex: cheap, unambiguous defects fixed in place, and intersections and
// near-contacts between surfaces removed by local vertex moves, without changing the topology.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/interface_complex.h"
#include "core/label_image.h"
#include "core/progress.h"

namespace tissuemesh::surface {

/// Options of repair(). Lengths in mm.
struct RepairOptions {
    /// Near-contacts: triangles of different patches sharing no vertex that are closer than this (vertex to
    /// face) are pushed apart until they are this far apart. 0: only intersections are removed.
    double gap_mm = 0;
    std::size_t max_rounds = 30; ///< rounds of local moves before repair() gives up
    /// With an image: a moved vertex must stay within this distance (voxels) of the voxels of each of its
    /// tissues, unless it was already further (as smooth() holds it).
    double max_depth_voxels = 0.5;
    std::size_t max_actions = 100; ///< store at most this many located actions in the report
};

/// What a repair action fixed.
enum class RepairKind {
    merged_vertex,        ///< a vertex at the same position as another was merged into it
    removed_duplicate,    ///< a triangle repeating another (same vertices, same tissues, same side) was dropped
    removed_degenerate,   ///< a triangle with a repeated vertex (zero area, no tissue behind it) was dropped
    collapsed_degenerate, ///< a zero-area triangle of three distinct vertices was collapsed away
    flipped_triangle,     ///< a triangle wound against all its neighbours of the same patch was turned
    intersection,         ///< a region where two triangles crossed was moved apart
    near_contact,         ///< a region where two patches came closer than the gap was moved apart
};

/// Kebab-case name of a kind ("merged-vertex", "near-contact").
std::string to_string(RepairKind kind);

/// One change, located for a user.
struct RepairAction {
    RepairKind kind = RepairKind::merged_vertex;
    Vec3 location_mm{0, 0, 0};
    std::vector<Label> tissues; ///< the tissues around it, ascending
    std::string description;    ///< one line, with tissue names and the location in mm
};

/// What repair() did. Counts are exact; actions are stored up to RepairOptions::max_actions.
struct RepairReport {
    std::size_t triangles_before = 0;
    std::size_t triangles_after = 0;
    std::size_t merged_vertices = 0;
    std::size_t removed_duplicates = 0;
    std::size_t removed_degenerate = 0;
    std::size_t collapsed_degenerate = 0;
    std::size_t flipped_triangles = 0;
    std::size_t self_intersections_before = 0;  ///< intersecting pairs within one patch
    std::size_t patch_intersections_before = 0; ///< intersecting pairs of different patches
    std::size_t near_contacts_before = 0;       ///< triangle pairs closer than the gap
    std::size_t near_contacts_after = 0;        ///< left where the image or the shapes allowed no move
    std::size_t rounds = 0;                     ///< rounds of local moves
    std::size_t moved_vertices = 0;             ///< distinct vertices moved
    double max_move_mm = 0;                     ///< largest distance a vertex moved
    std::vector<RepairAction> actions;

    /// Whether anything changed.
    bool changed() const;
};

/// Repairs `complex` in place. First the cheap defects where the fix is unambiguous: coincident vertices
/// are merged, repeated triangles (same vertices, tissues and side) dropped, zero-area triangles dropped
/// (repeated vertex) or collapsed away (three distinct collinear vertices), triangles wound against every
/// neighbour of their patch turned. No tissue is ever dropped: a triangle whose tissues differ from its
/// double's stays, and the final check reports it. Then intersections and, with RepairOptions::gap_mm,
/// near-contacts between patches are removed locally: the vertices of the triangles involved (and, in
/// later rounds, their neighbours) are pushed apart along their normals, each away from the tissue the
/// two patches share (so a thin layer gets its thickness back), or smoothed towards their neighbours
/// where a patch folds through itself. Every move goes through the editor (surface/detail/complex_editor.h)
/// in a mode that accepts a move only when the moved triangles meet no more triangles than before, so
/// the number of intersections never grows; moves never change the topology. With `image`, moved
/// vertices stay near the voxels of their tissues (RepairOptions::max_depth_voxels).
/// @post the complex passes check_complex(), with the same tissues as the input
/// @throws InputError when indices are out of range or options are invalid
/// @throws AlgorithmError when a defect remains that repair cannot fix (holes, a tissue touching itself
///         along an edge, opposite doubles, intersections local moves cannot undo), naming the first one
RepairReport repair(InterfaceComplex& complex, const RepairOptions& options = {}, const LabelImage* image = nullptr,
                    const Progress& progress = {});

} // namespace tissuemesh::surface

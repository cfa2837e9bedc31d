// The surface checker: is an interface complex fit for tetrahedralization?
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "core/interface_complex.h"
#include "core/progress.h"

namespace tissuemesh::surface {

/// What can be wrong with an interface complex. Every kind is an error except needle_triangle.
enum class DefectKind {
    open_edge,            ///< a tissue's surface has a boundary edge (a hole)
    orientation_conflict, ///< a tissue's surface uses an edge twice in the same direction (flipped triangle)
    non_manifold_edge,    ///< a tissue touches itself along an edge (more than 2 of its triangles share it)
    inverted_tissue,      ///< a closed tissue encloses a negative volume (labels swapped, or unbounded)
    tangled_junction,     ///< around a junction edge the triangles turn in an order their tissues contradict
    degenerate_triangle,  ///< repeated vertex or exactly collinear vertices (zero area)
    duplicate_triangle,   ///< two triangles on the same three vertices
    duplicate_vertex,     ///< two vertex indices at the same coordinates, both used by triangles
    self_intersection,    ///< two triangles of the same patch (same tissue pair) intersect
    patch_intersection,   ///< triangles of two different patches intersect
    needle_triangle,      ///< warning: an angle below CheckOptions::needle_angle_deg
};
inline constexpr std::size_t defect_kind_count = 11;

/// Kebab-case name of a kind ("open-edge", "patch-intersection").
std::string_view to_string(DefectKind kind);
/// False only for warnings (needle_triangle).
bool is_error(DefectKind kind);

/// One defect, located and explained for a user.
struct Defect {
    DefectKind kind = DefectKind::open_edge;
    /// One line naming the tissues (by name when the complex has names) and the location in mm, e.g.
    /// "intersection between scalp|skull triangle 123 and skull|CSF triangle 456 near (31.2, -4, 55.8) mm".
    std::string description;
    Vec3 location_mm{0, 0, 0};            ///< a point on the defect, world mm
    std::vector<Label> tissues;           ///< the tissues involved, ascending
    std::vector<std::uint32_t> triangles; ///< the triangles involved (indices into the complex)
};

/// The surface of one tissue: its triangles oriented outward (from the tissue into its neighbour).
struct TissueCheck {
    std::size_t triangles = 0;             ///< triangles with this tissue on one side
    bool closed = true;                    ///< no open edge
    bool oriented = true;                  ///< no orientation conflict
    std::size_t open_edges = 0;            ///< edges used an odd number of times
    std::size_t orientation_conflicts = 0; ///< edges used evenly but not in matched opposite pairs
    std::size_t non_manifold_edges = 0;    ///< edges where the tissue touches itself
    std::size_t components = 0;            ///< edge-connected pieces of the surface
    /// Signed volume enclosed by the outward surface (divergence theorem), mm^3. Meaningful when closed
    /// and oriented; positive for bounded tissues, minus the enclosed volume for the (unbounded) background.
    double volume_mm3 = 0;
};

/// Everything check_complex() found. Defects are stored up to CheckOptions::max_defects_per_kind per
/// kind, in a deterministic order; counts are exact.
struct CheckReport {
    std::size_t vertices = 0; ///< vertices used by triangles
    std::size_t triangles = 0;
    std::size_t edges = 0;          ///< distinct undirected edges
    std::size_t junction_edges = 0; ///< edges shared by three or more triangles (junction curves)
    bool intersections_checked = false;
    std::map<Label, TissueCheck> tissues; ///< every label on either side of a triangle
    std::vector<Defect> defects;
    std::array<std::size_t, defect_kind_count> counts{}; ///< exact number of defects per kind

    std::size_t count(DefectKind kind) const { return counts[static_cast<std::size_t>(kind)]; }
    std::size_t error_count() const;
    std::size_t warning_count() const;
    /// Fit for tetrahedralization: no error (warnings do not count).
    bool ok() const { return error_count() == 0; }
    /// The first stored error, or nullptr.
    const Defect* first_error() const;
};

/// Options of check_complex(). Angles in degrees.
struct CheckOptions {
    double needle_angle_deg = 1.0;          ///< warn about triangles with an angle below this
    std::size_t max_defects_per_kind = 100; ///< store at most this many defects of each kind
    bool check_intersections = true;        ///< false skips the (most expensive) intersection test
};

/// The closed shells around `tissue`: the edge-connected pieces of the triangles with the tissue on one side
/// (the pieces check_complex() counts as a tissue's components), in the order of their first triangle, each
/// in increasing order. A tissue never touches itself along an edge, so each shell bounds one connected piece
/// of it; a piece bounds itself with one shell, or more when it holds cavities (a hollow ball: two spheres).
std::vector<std::vector<std::uint32_t>> tissue_shells(const InterfaceComplex& complex, Label tissue);

/// Checks that `complex` is fit for tetrahedralization: every tissue's outward surface is closed and
/// consistently oriented and encloses a positive volume (negative for the background), no tissue
/// touches itself along an edge, around every junction edge the tissue between neighbouring triangles
/// is the same seen from both (edge_fan.h), no degenerate or duplicate triangle, no duplicate vertex, and no two
/// triangles meet other than at shared vertices and edges (exact predicates). Needles are warnings.
/// Runs in O(T log T); a million triangles take seconds.
/// @throws InputError when indices are out of range, sizes disagree or a coordinate is not finite
CheckReport check_complex(const InterfaceComplex& complex, const CheckOptions& options = {},
                          const Progress& progress = {});

/// What a user can do about the errors in `report`, as one clause: tm-repair where every error is of a
/// kind it may fix (coincident vertices, repeated, zero-area or flipped triangles, intersections; open
/// edges too when doubled vertices or triangles may be their cause), else re-extraction with tm-extract
/// (holes, a tissue touching itself, an inverted tissue).
std::string repair_hint(const CheckReport& report);

/// The smallest angle (degrees) a tissue (or the background, which tm-tetra meshes where tissues enclose it)
/// fills about an edge, between neighbouring triangles: every tet at the edge lies inside such an angle, so no
/// tet mesh that keeps the complex has a larger smallest dihedral angle there. 360 when no edge has two triangles.
double smallest_tissue_sector_deg(const InterfaceComplex& complex);

/// For steps that need a valid complex: runs check_complex() and throws when it is not fit.
/// @throws InputError naming `what`, the number of errors and the first defect, with repair_hint()
///         (which always ends "re-extract it with tm-extract ..."); also when the complex has no triangle.
void require_fit_for_tetrahedralization(const InterfaceComplex& complex, const std::string& what);

} // namespace tissuemesh::surface

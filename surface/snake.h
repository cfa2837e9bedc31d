// Active contours (Kass, Witkin and Terzopoulos 1988, in 3-D): closed triangle surfaces that move under
// internal forces (tension, rigidity) and an image force until they settle on a tissue boundary, with
// adaptive resolution and no self-intersection; several nested snakes make one interface complex.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/interface_complex.h"
#include "core/progress.h"
#include "surface/snake_field.h"

namespace tissuemesh::surface {

/// One snake: the triangles of `pair` (either orientation) in the complex, `pair.from` inside, driven
/// towards the zero level of `field` (positive inside).
struct SnakeTarget {
    LabelPair pair;
    PotentialField field;
};

/// Options of evolve_snakes(). Weights are fractions of a step per iteration (dimensionless); lengths in
/// voxels of the smallest spacing of the first field unless the name says mm; angles in degrees.
struct SnakeOptions {
    double image_weight = 0.8;    ///< fraction of the field's distance estimate phi/|grad phi| moved per iteration
    double tension = 0.2;         ///< weight of the umbrella Laplacian (shrinks and evens out the surface)
    double rigidity = 0.05;       ///< weight of the bi-Laplacian (resists bending)
    double balloon_voxels = 0;    ///< constant motion along the outward normal per iteration (negative deflates)
    double max_step_voxels = 0.5; ///< no vertex moves more than this in one iteration
    double target_edge_mm = 0;    ///< adaptive resolution: edge length sought (0: 2 voxels)
    /// > 0: curvature-adapted resolution, edges shortened where the chord of the local curvature circle
    /// would leave the surface by more than this (never below a quarter of target_edge_mm)
    double max_chord_error_mm = 0;
    std::size_t resolution_every = 5;    ///< split/collapse/flip pass every this many iterations (0: never)
    double min_separation_voxels = 0.25; ///< distance kept between different snakes (and folds of one)
    std::size_t max_iterations = 300;    ///< iteration cap
    double tolerance_voxels = 0.01;      ///< converged when no vertex moves more than this in an iteration
    double min_angle_deg = 5;            ///< no edit may create a smaller angle (unless not worse)
    double max_normal_change_deg = 45;   ///< one edit may tilt a triangle at most this much
};

/// What evolve_snakes() did. `converged` false means the iteration cap stopped it (the surfaces are still
/// valid, only not settled).
struct SnakeReport {
    std::size_t iterations = 0;
    bool converged = false;
    double last_max_motion_mm = 0;   ///< largest vertex motion of the last iteration
    std::size_t moves = 0;           ///< vertex moves made (full or shortened)
    std::size_t shortened_moves = 0; ///< moves made only at half or a quarter of their step
    std::size_t refused_moves = 0;   ///< moves the validity checks refused even at a quarter step
    std::size_t splits = 0;
    std::size_t collapses = 0;
    std::size_t flips = 0;
    std::size_t triangles = 0;             ///< at the end
    double mean_abs_field_distance_mm = 0; ///< mean |phi / |grad phi|| over the final vertices
};

/// Moves the snakes of `complex` (closed, nested, non-intersecting surfaces, one per target) to the zero
/// levels of their fields. Each iteration every vertex moves by
///     image_weight * clamp(phi / |grad phi|) * n + balloon * n + tension * L(v) - rigidity * L(L(v)),
/// clamped to max_step_voxels, where n is the outward vertex normal, L the umbrella Laplacian (mean of the
/// neighbours minus the vertex) and phi / |grad phi| the field's first-order signed distance to its zero
/// level. Every move goes through the validity checks of surface/detail/complex_editor.h (no fold, no
/// intersection, min_separation kept); a move that would break one is retried at half and a quarter of its
/// length, then skipped. Every resolution_every iterations edges longer than 4/3 of the target are split,
/// shorter than 4/5 collapsed, and edges flipped towards valence 6 (checked the same way).
/// Stops when the largest vertex motion of an iteration is below tolerance_voxels (converged) or at
/// max_iterations.
/// @pre  `complex` passes check_complex(); each triangle's pair is one target's pair (either orientation)
/// @post it still passes check_complex(), each snake oriented from its `pair.from` to `pair.to`
/// @throws InputError when a precondition or an option range does not hold
SnakeReport evolve_snakes(InterfaceComplex& complex, const std::vector<SnakeTarget>& targets,
                          const SnakeOptions& options = {}, const Progress& progress = {});

/// A closed triangulated ellipsoid with axis-aligned semi-axes `radii_mm` around `centre_mm`, edges of
/// about `edge_mm` (a subdivided icosahedron, stretched), oriented from `pair.from` (inside) to `pair.to`.
/// @throws InputError when a radius or the edge length is not positive
InterfaceComplex ellipsoid_surface(const Vec3& centre_mm, const Vec3& radii_mm, double edge_mm, LabelPair pair);

/// Targets for nested tissues of a label image, outermost first: snake k seeks the boundary of tissue k
/// and everything it encloses (enclosed_region()), with the pair {tissues[k], tissues[k-1]} (the first
/// against the image's background, label 0). The fields are the regions' indicators smoothed by a
/// Gaussian of `sigma_mm` (label_potential()).
/// @throws InputError when a tissue is missing from the image, listed twice, or is the background
std::vector<SnakeTarget> nested_label_targets(const LabelImage& image, const std::vector<Label>& tissues_outer_first,
                                              double sigma_mm);

/// Start surfaces for `targets`: per target an axis-aligned ellipsoid around the centre of the bounding box of
/// its field's positive region, semi-axes `scale` times the box's half extents (plus half a voxel), edges of
/// about `edge_mm`, labelled with the target's pair. Nested regions give nested ellipsoids when their boxes
/// are nested (evolve_snakes() checks that they do not meet).
/// @throws InputError when a field has no positive voxel or scale is not positive
InterfaceComplex bounding_ellipsoids(const std::vector<SnakeTarget>& targets, double scale, double edge_mm);

/// Fits a start surface read from a file to `targets`: left as it is when every triangle's pair is a target's
/// pair (either orientation); with one target and one pair in the file, every triangle takes the target's pair
/// (the file's `from` side becoming the target's `from`).
/// @throws InputError naming `what` otherwise
void label_start_surface(InterfaceComplex& complex, const std::vector<SnakeTarget>& targets, const std::string& what);

/// Appends `part`'s vertices and triangles to `complex` (indices shifted).
void append_complex(InterfaceComplex& complex, const InterfaceComplex& part);

} // namespace tissuemesh::surface

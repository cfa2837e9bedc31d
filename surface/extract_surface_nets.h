// Tissue interfaces from labels by multi-label surface nets: one vertex per grid cube where labels
// meet, smoothed inside its cube, so the complex is ready for decimation in one fast step.
#pragma once

#include <cstddef>

#include "core/interface_complex.h"
#include "core/label_image.h"
#include "core/progress.h"
#include "surface/extract_interfaces.h"

namespace tissuemesh::surface {

/// How surface-net vertices are smoothed. Lengths in voxels (index space), angles in degrees.
struct NetSmoothOptions {
    /// Taubin lambda|mu pairs (0: the raw net, vertices at cube centres).
    std::size_t iterations = 16;
    double lambda = 0.6307; ///< shrinking step factor (Taubin 1995: pass band k_PB = 0.1)
    double mu = -0.6732;    ///< inflating step factor, |mu| > lambda
    /// Pairs run between two checks (each step keeps every vertex in its box and near its voxels; the
    /// checks between triangles judge the net move of the run, offenders go back to its start).
    std::size_t pairs_per_check = 4;
    /// A vertex stays this far inside its cube (voxels). Two cubes' vertices are at least twice this apart
    /// across a shared face, so a one-voxel layer keeps at least this thickness.
    double margin_voxels = 0.1;
    /// A vertex must stay within this distance (voxels) of the voxels of each tissue it separates (three
    /// where more meet), as tm-smooth's --max-depth-voxels; in (0, 1].
    double max_depth_voxels = 0.5;
    double min_angle_deg = 2.0;        ///< no move may leave a triangle with a smaller angle (unless not worse)
    double max_normal_change_deg = 30; ///< one step may tilt a triangle at most this much
};

/// What extract_surface_nets() did.
struct SurfaceNetsReport {
    std::size_t mixed_cubes = 0;       ///< grid cubes whose corner labels differ
    std::size_t fallback_cubes = 0;    ///< of them, kept as their tetrahedra (see surface/detail/surface_net.h)
    std::size_t iterations = 0;        ///< smoothing pairs made
    std::size_t moves = 0;             ///< vertex moves kept (over all steps)
    std::size_t refused_by_image = 0;  ///< moves the voxel evidence refused
    std::size_t refused_by_checks = 0; ///< moves put back because a triangle would fold, shrink or meet another
    double mean_displacement_mm = 0;   ///< from the cube centres to the final places
    double max_displacement_mm = 0;
};

/// Builds the interface complex of `image` by multi-label surface nets and smooths it.
///
/// Topology: the complex has the connectivity rule and priority rule of extract_interfaces() (the
/// 14-neighbourhood, or the priority's), and every invariant of its output: closed and oriented per
/// tissue, a tissue pair per triangle, junction curves shared, the triangle order around junction edges,
/// no intersection, sides `from` the larger label and the background `to`. See surface/detail/surface_net.h
/// for the construction and the one rule that decides ambiguous cubes.
///
/// Smoothing (NetSmoothOptions): Taubin's lambda|mu filter with uniform weights, Jacobi steps (every
/// vertex moves from the positions of the step before, so the result does not depend on the thread
/// count): vertices inside a patch towards the mean of their neighbours, vertices on a junction curve
/// towards the mean of their two curve neighbours, corners of curves fixed. Each vertex stays inside its
/// cube shrunk by the margin and near the voxels of its tissues. Because every vertex keeps to its own
/// cube, a triangle can only meet triangles with a vertex in the cubes around its own, so every step is
/// checked locally (a fixed list of neighbouring pairs, built once from the cubes): triangles that would
/// meet, fold (tilt beyond the limit), degenerate or get a small angle put their vertices back, until none does.
/// @throws InputError as extract_interfaces(), and when smoothing options are out of range
InterfaceComplex extract_surface_nets(const LabelImage& image, const ExtractOptions& options = {},
                                      const NetSmoothOptions& smoothing = {}, const Progress& progress = {},
                                      SurfaceNetsReport* report = nullptr);

} // namespace tissuemesh::surface

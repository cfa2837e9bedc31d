// Smoothing of a surface net that cannot cross: every vertex keeps to its own cube, so only triangles
// with vertices in neighbouring cubes can meet, and every step is checked against a fixed list of such
// pairs (built once from the cubes) and inside each vertex's star.
#pragma once

#include <vector>

#include "core/label_image.h"
#include "core/progress.h"
#include "surface/detail/surface_net.h"
#include "surface/extract_surface_nets.h"

namespace tissuemesh::surface::detail {

/// @throws InputError when an option is out of range (names it and the range)
void validate(const NetSmoothOptions& options);

/// Vertices of kind NetVertexKind::cube that lie outside their cube shrunk by `margin_voxels` (or, for the
/// others, away from where the net put them): the invariant the smoothing's local checks rest on. A vertex
/// outside its box could meet triangles the fixed list of neighbouring pairs does not hold.
std::size_t vertices_outside_boxes(const SurfaceNet& net, double margin_voxels);

/// Smooths `net` in place (see extract_surface_nets()); `label_map` and `background` as given to
/// build_surface_net(), for the voxel evidence. Fills the smoothing figures of `report`.
/// @pre net is a valid complex (as build_surface_net() makes it)   @post still valid, same triangles
/// @throws AlgorithmError when a vertex ended outside its box (vertices_outside_boxes(): a bug, never seen)
void smooth_net(SurfaceNet& net, const LabelImage& image, const std::vector<Label>& label_map, Label background,
                const NetSmoothOptions& options, const Progress& progress, SurfaceNetsReport& report);

} // namespace tissuemesh::surface::detail

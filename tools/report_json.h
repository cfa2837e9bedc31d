// The JSON form of the libraries' reports, one place per struct, that the tools' --json summaries are made of:
// `nlohmann::json j = report;`. Keys are the field names. A field left out of a list here is one no summary
// has carried under its own name: a tool adds it under the name its summary has (tm-tetra's tetgen_switches)
// or leaves it out, so that no key of a summary changed when the tools took their forms from here.
// The render reports are tm-render's own (tools/tm_render.cpp): the other tools do not compile against render/.
#pragma once

#include <nlohmann/json.hpp>

#include "image/label_statistics.h"
#include "surface/check_complex.h"
#include "surface/decimate.h"
#include "surface/extract_surface_nets.h"
#include "surface/remesh.h"
#include "surface/repair.h"
#include "surface/smooth.h"
#include "surface/snake.h"
#include "volume/assess.h"
#include "volume/check_mesh.h"
#include "volume/improve_mesh.h"
#include "volume/interface_distance.h"
#include "volume/refine.h"
#include "volume/tetrahedralize.h"

namespace tissuemesh::image {

// Not index_min, index_max, bounds_mm: tm-info writes them as bbox_index_min, ..., bbox_mm_max.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(LabelSummary, label, name, voxels, volume_mm3, components6, components26, touches,
                                   border_voxels, thin_voxels, islands, island_voxels, warnings)
// Not labels: tm-info writes them with the bounding boxes above.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(LabelStatistics, dims, spacing_mm, origin_mm, direction, orientation, bounds_mm,
                                   voxel_count)

} // namespace tissuemesh::image

namespace tissuemesh::surface {

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(TissueCheck, triangles, closed, oriented, open_edges, orientation_conflicts,
                                   non_manifold_edges, components, volume_mm3)
// Not iterations: tm-extract writes it as smooth_iterations.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(SurfaceNetsReport, mixed_cubes, fallback_cubes, moves, refused_by_image,
                                   refused_by_checks, mean_displacement_mm, max_displacement_mm)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(SmoothReport, iterations, moves, refused_by_image, refused_by_checks, fit_moves,
                                   fixed_vertices, mean_displacement_mm, max_displacement_mm)
// Not refused_by_checks (the sum of the five refusals after it).
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(DecimateReport, triangles_before, triangles_after, collapses, splits, slabs,
                                   contractions, contracted_vertices, contractions_refused, refused_by_distance,
                                   refused_by_length, refused_topology, refused_shape, refused_fold,
                                   refused_intersection, refused_gap, refused_wedge, max_distance_mm)
// Not max_distance_mm: tm-remesh writes it as max_distance_to_input_mm.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(RemeshReport, triangles_before, triangles_after, splits, collapses, flips, moves,
                                   refused, refused_by_voxels, slabs, min_angle_before_deg, min_angle_after_deg,
                                   min_sector_before_deg, min_sector_after_deg, mean_edge_after_mm, thin_triangles)
// Not actions: tm-repair writes them with their kinds' names.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(RepairReport, triangles_before, triangles_after, merged_vertices, removed_duplicates,
                                   removed_degenerate, collapsed_degenerate, flipped_triangles,
                                   self_intersections_before, patch_intersections_before, near_contacts_before,
                                   near_contacts_after, rounds, moved_vertices, max_move_mm)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(SnakeReport, iterations, converged, last_max_motion_mm, moves, shortened_moves,
                                   refused_moves, splits, collapses, flips, triangles, mean_abs_field_distance_mm)

} // namespace tissuemesh::surface

namespace tissuemesh::volume {

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ShapeFigures, min_dihedral_deg, max_dihedral_deg, p1_min_dihedral_deg,
                                   tets_under_10_deg, tets_under_20_deg, tets)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ImproveReport, before, after, smoothed_nodes, edges_removed, faces_removed,
                                   interface_edges_flipped, nodes_inserted, nodes_inserted_on_interfaces,
                                   refused_by_voxels, refused_crossing_boundary, passes, parts, bands, seconds,
                                   cpu_seconds)
// Not input_vertices; not switches and seconds: tm-tetra writes them as tetgen_switches and
// tetrahedralize_seconds; not improved and improvement: tm-tetra writes the improvement when there is one.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(TetrahedralizeReport, input_triangles, nodes, tets, layer_points, steiner_points,
                                   interface_faces, split_interface_triangles, min_dihedral_deg, max_radius_edge_ratio,
                                   tets_over_volume_bound)
// Not agreeing_voxels (the Dice says it).
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(TissueAssessment, image_voxels, mesh_voxels, dice, mesh_volume_mm3, voxel_volume_mm3,
                                   volume_error_mm3, error_volume_mm3)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(TissueMeshStats, tets, volume_mm3, components, voxel_volume_mm3, dice)
// Not tissues, quality, problems: tm-check-mesh writes the tissues with their names and some quality figures.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(MeshCheckReport, nodes, tets, faces, inverted_tets, flat_tets, nonconforming_faces,
                                   open_boundary_edges, boundary_crossings, unused_nodes, missing_interface_faces,
                                   mislabelled_interface_faces, unmarked_interfaces)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(InterfaceDistance, nodes, max_node_mm, mean_node_mm, faces, max_face_mm,
                                   mean_face_mm, unmatched_faces)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(RefineIteration, iteration, nodes, tets, added_nodes, reassessed_tets,
                                   total_error_volume_mm3, worst_quality_key, seconds)

} // namespace tissuemesh::volume

// The JSON form of the libraries' reports, one place per struct, that the tools' --json summaries are made of:
// `nlohmann::json j = report;`. Keys are the field names. A field left out of a list here is one no summary
// has carried under its own name: a tool adds it under the name its summary has (tm-tetra's tetgen_switches)
// or leaves it out, so that no key of a summary changed when the tools took their forms from here.
#pragma once

#include <nlohmann/json.hpp>

#include "volume/assess.h"
#include "volume/check_mesh.h"
#include "volume/improve_mesh.h"
#include "volume/interface_distance.h"
#include "volume/refine.h"
#include "volume/tetrahedralize.h"

namespace tissuemesh::volume {

NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ShapeFigures, min_dihedral_deg, max_dihedral_deg, p1_min_dihedral_deg,
                                   tets_under_10_deg, tets_under_20_deg, tets)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(ImproveReport, before, after, smoothed_nodes, edges_removed, faces_removed,
                                   interface_edges_flipped, nodes_inserted, nodes_inserted_on_interfaces, passes,
                                   seconds, cpu_seconds)
// Not input_vertices; not switches and seconds: tm-tetra writes them as tetgen_switches and
// tetrahedralize_seconds; not improved and improvement: tm-tetra writes the improvement when there is one.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(TetrahedralizeReport, input_triangles, nodes, tets, steiner_points, interface_faces,
                                   split_interface_triangles, min_dihedral_deg, max_radius_edge_ratio,
                                   tets_over_volume_bound)
// Not agreeing_voxels (the Dice says it).
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(TissueAssessment, image_voxels, mesh_voxels, dice, mesh_volume_mm3, voxel_volume_mm3,
                                   volume_error_mm3, error_volume_mm3)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(TissueMeshStats, tets, volume_mm3, components, voxel_volume_mm3, dice)
// Not tissues, quality, problems: tm-check-mesh writes the tissues with their names and some quality figures.
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(MeshCheckReport, nodes, tets, faces, inverted_tets, flat_tets, nonconforming_faces,
                                   open_boundary_edges, unused_nodes, missing_interface_faces,
                                   mislabelled_interface_faces, unmarked_interfaces)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(InterfaceDistance, nodes, max_node_mm, mean_node_mm, faces, max_face_mm,
                                   mean_face_mm, unmatched_faces)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(RefineIteration, iteration, nodes, tets, added_nodes, reassessed_tets,
                                   total_error_volume_mm3, worst_quality_key, seconds)

} // namespace tissuemesh::volume

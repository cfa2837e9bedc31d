// Topological and volumetric checks of check_complex(): per-tissue surfaces and edge counts.
#pragma once

#include <set>

#include "surface/detail/defect_log.h"

namespace tissuemesh::surface::detail {

/// Fills report.tissues: each tissue's surface, oriented outward (a triangle as stored when the tissue
/// is its `from`, reversed when it is its `to`), is scanned edge by edge. An edge used an odd number of
/// times is open; used evenly but not in opposite pairs, an orientation conflict; used more than twice,
/// the tissue touches itself (non-manifold). Also counts edge-connected components and the enclosed
/// volume.
void check_tissue_surfaces(DefectLog& log, CheckReport& report);

/// Logs closed, oriented tissues whose enclosed volume has the wrong sign (not positive, or for the
/// background not negative) as inverted. Tissues in `crossing` (involved in an intersection) are
/// skipped: the volume of a self-crossing surface says nothing about its orientation.
void check_volume_signs(DefectLog& log, const CheckReport& report, const std::set<Label>& crossing);

/// Sets report.edges (distinct undirected edges of `merged`: the triangles with coincident vertices
/// merged) and report.junction_edges (shared by 3+ triangles), and logs every junction edge around which
/// the triangles not marked in `skip` turn in an order their tissues contradict (edge_fan.h). Triangles
/// lying on one another along an edge are left to the intersection test.
void check_edges(DefectLog& log, const std::vector<Triangle>& merged, const std::vector<char>& skip,
                 CheckReport& report);

} // namespace tissuemesh::surface::detail

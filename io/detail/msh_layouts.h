// The .msh layouts of the tools our users run: SimNIBS's numbering and DUNEuro's conductor files.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/tet_mesh.h"
#include "io/detail/msh2_format.h"

namespace tissuemesh::io::detail {

/// The faces SimNIBS's mesher puts in a head mesh, rebuilt from the tets alone (as its
/// reconstruct_unique_surface does): one triangle per tet face between two tags, tagged simnibs_face_tag() of
/// them, and one per face on the outside, tagged 1005; each oriented with its normal out of the tet whose tag it
/// carries (out of the mesh on the outside). Tets take `tags` (label -> SimNIBS tag); physical = elementary.
/// Faces come in the order of their sorted vertex indices (deterministic).
/// @throws InputError when a tet face is shared by more than two tets (the mesh does not conform)
Msh2Elements simnibs_elements(const TetMesh& mesh, const std::map<Label, int>& tags);

/// DUNEuro's layout: tets only (dune-grid would take triangles for boundary segments), tissue i (in ascending
/// label order) tagged `offset + i` as physical and elementary tag, $PhysicalNames after $EndElements with
/// spaces in names as '_'.
Msh2Elements duneuro_elements(const TetMesh& mesh, int offset);

/// The conductivity file DUNEuro reads beside the mesh: the conductivity (S/m) of tissue i on line i, in
/// ascending label order, nothing else (its reader stops at anything but a number).
/// @throws InputError naming a tissue of the mesh that has no positive conductivity in `conductivities`
std::string duneuro_conductivity_file(const TetMesh& mesh, const std::map<Label, double>& conductivities);

} // namespace tissuemesh::io::detail

// The sources of a lead field: located once for all of them, and their loads per lead-field column.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "fem/lead_field.h"

namespace tissuemesh::fem::detail {

/// How messages name source `index` (0-based): its name, or "source N" (1-based).
std::string source_label(const LeadFieldSource& source, std::size_t index);

/// The unit moments (A*m) of a source's columns: its orientation, or x, y and z.
std::vector<Vec3> column_moments(const LeadFieldSource& source);

/// The tet of every source, and its tissue.
/// @throws InputError naming the first source outside the mesh, or in a tissue not in `allowed` (empty: any)
std::vector<std::uint32_t> locate_sources(const TetMesh& mesh, const std::vector<LeadFieldSource>& sources,
                                          const std::vector<Label>& allowed);

/// A column's load for its unit moment: currents (A per A*m) on mesh nodes, increasing.
struct ColumnLoad {
    std::vector<std::uint32_t> nodes;
    std::vector<double> currents_a;
};

/// The loads of every column, in column order, for Venant or partial integration (`tets` from
/// locate_sources).
/// @throws AlgorithmError when a Venant source has no solution (a flat tet next to it)
std::vector<ColumnLoad> column_loads(const TetMesh& mesh, const Conductivities& conductivities,
                                     const std::vector<LeadFieldSource>& sources,
                                     const std::vector<std::uint32_t>& tets, DipoleModel model,
                                     const VenantOptions& venant);

} // namespace tissuemesh::fem::detail

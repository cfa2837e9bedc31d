#include "fem/detail/lead_field_sources.h"

#include <algorithm>

#include "core/error.h"
#include "fem/assemble.h"
#include "fem/detail/point_location.h"
#include "fem/detail/venant.h"

namespace tissuemesh::fem::detail {
namespace {

std::string tissue_name(const TetMesh& mesh, Label label)
{
    const auto found = mesh.names.find(label);
    return found == mesh.names.end() ? concat("tissue ", label) : concat(found->second, " (", label, ")");
}

std::string where(const LeadFieldSource& source)
{
    const Vec3& p = source.position_mm;
    return concat("(", format_mm(p[0]), ", ", format_mm(p[1]), ", ", format_mm(p[2]), ") mm");
}

} // namespace

std::string source_label(const LeadFieldSource& source, std::size_t index)
{
    return source.name.empty() ? concat("source ", index + 1) : source.name;
}

std::vector<Vec3> column_moments(const LeadFieldSource& source)
{
    if (source.orientation) return {*source.orientation};
    return {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
}

std::vector<std::uint32_t> locate_sources(const TetMesh& mesh, const std::vector<LeadFieldSource>& sources,
                                          const std::vector<Label>& allowed)
{
    std::vector<Vec3> points;
    for (const LeadFieldSource& source : sources) points.push_back(source.position_mm);
    const std::vector<std::uint32_t> tets = locate_points(mesh, points);
    for (std::size_t s = 0; s < sources.size(); ++s) {
        if (tets[s] == outside_mesh)
            throw InputError(concat(source_label(sources[s], s), " at ", where(sources[s]), " lies outside the mesh; ",
                                    "give positions inside the head in the mesh's coordinates (mm)"));
        const Label tissue = mesh.tet_labels[tets[s]];
        if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), tissue) == allowed.end()) {
            std::string names;
            for (const Label label : allowed) names += (names.empty() ? "" : ", ") + tissue_name(mesh, label);
            throw InputError(concat(source_label(sources[s], s), " at ", where(sources[s]), " lies in ",
                                    tissue_name(mesh, tissue), ", not in the source tissues (", names,
                                    "); move it or allow that tissue"));
        }
    }
    return tets;
}

std::vector<ColumnLoad> column_loads(const TetMesh& mesh, const Conductivities& conductivities,
                                     const std::vector<LeadFieldSource>& sources,
                                     const std::vector<std::uint32_t>& tets, DipoleModel model,
                                     const VenantOptions& venant)
{
    std::vector<ColumnLoad> loads;
    if (model == DipoleModel::partial_integration) {
        // b_i = p . grad(phi_i) in the source's tet.
        for (std::size_t s = 0; s < sources.size(); ++s) {
            const P1Element element = p1_element(mesh, tets[s]);
            const Tet& tet = mesh.tets[tets[s]];
            std::array<std::size_t, 4> order{0, 1, 2, 3};
            std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return tet[a] < tet[b]; });
            for (const Vec3& moment : column_moments(sources[s])) {
                ColumnLoad load;
                for (const std::size_t k : order) {
                    load.nodes.push_back(tet[k]);
                    load.currents_a.push_back(dot(moment, element.gradients[k]));
                }
                loads.push_back(std::move(load));
            }
        }
        return loads;
    }
    // Venant: the tets around each source's nearest corner, found in one pass for all of them.
    std::vector<std::uint32_t> corners;
    for (std::size_t s = 0; s < sources.size(); ++s)
        corners.push_back(nearest_corner(mesh, tets[s], sources[s].position_mm));
    const std::vector<std::vector<std::uint32_t>> around = tets_around(mesh, corners);
    for (std::size_t s = 0; s < sources.size(); ++s) {
        const VenantBasis basis =
            venant_basis(mesh, conductivities, sources[s].position_mm, s, tets[s], around[s], venant);
        for (const Vec3& moment : column_moments(sources[s])) {
            ColumnLoad load{basis.nodes, std::vector<double>(basis.nodes.size(), 0.0)};
            for (std::size_t k = 0; k < basis.nodes.size(); ++k)
                for (std::size_t axis = 0; axis < 3; ++axis)
                    load.currents_a[k] += moment[axis] * basis.unit_currents_a[axis][k];
            loads.push_back(std::move(load));
        }
    }
    return loads;
}

} // namespace tissuemesh::fem::detail

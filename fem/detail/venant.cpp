#include "fem/detail/venant.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "core/error.h"
#include "fem/assemble.h"
#include "fem/detail/sources.h"

namespace tissuemesh::fem::detail {
namespace {

bool same_conductivity(const Mat3& a, const Mat3& b)
{
    for (int k = 0; k < 9; ++k)
        if (std::abs(a[k] - b[k]) > 1e-12 * (std::abs(a[k]) + std::abs(b[k]))) return false;
    return true;
}

// The nodes of the monopoles (see venant.h), increasing: those of the tets `around` the corner of tet `source`
// nearest the dipole that conduct like `source`.
std::vector<std::uint32_t> patch_nodes(const TetMesh& mesh, const Conductivities& conductivities, std::size_t source,
                                       const std::vector<std::uint32_t>& around)
{
    const Mat3& sigma = conductivities.of(mesh.tet_labels[source], source);
    std::vector<std::uint32_t> nodes;
    for (const std::uint32_t t : around) {
        if (!same_conductivity(conductivities.of(mesh.tet_labels[t], t), sigma)) continue;
        nodes.insert(nodes.end(), mesh.tets[t].begin(), mesh.tets[t].end());
    }
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    return nodes;
}

// The traceless part of the second moments of offsets `d` (3 by #nodes), one row per component in an
// orthonormal basis of the traceless symmetric 3x3 matrices: for currents q, |rows * q| is the Frobenius
// norm of the traceless part of sum q_k d_k d_k^T.
Eigen::MatrixXd traceless_second_moments(const Eigen::MatrixXd& d)
{
    const double r2 = std::sqrt(2.0), r6 = std::sqrt(6.0);
    Eigen::MatrixXd rows(5, d.cols());
    for (Eigen::Index k = 0; k < d.cols(); ++k) {
        const double x = d(0, k), y = d(1, k), z = d(2, k);
        rows.col(k) << r2 * x * y, r2 * y * z, r2 * z * x, (x * x - y * y) / r2, (x * x + y * y - 2 * z * z) / r6;
    }
    return rows;
}

} // namespace

std::uint32_t nearest_corner(const TetMesh& mesh, std::size_t source, const Vec3& position_mm)
{
    const Tet& tet = mesh.tets[source];
    std::uint32_t nearest = tet[0];
    for (const std::uint32_t node : tet)
        if (distance(mesh.vertices[node], position_mm) < distance(mesh.vertices[nearest], position_mm)) nearest = node;
    return nearest;
}

VenantBasis venant_basis(const TetMesh& mesh, const Conductivities& conductivities, const Vec3& position_mm,
                         std::size_t index, std::size_t source, const std::vector<std::uint32_t>& around,
                         const VenantOptions& options)
{
    if (!(options.reference_length_mm > 0) || !(options.regularisation > 0) || options.weighting_exponent < 0)
        throw InputError(concat("Venant options: reference length ", options.reference_length_mm,
                                " mm, regularisation ", options.regularisation, ", weighting exponent ",
                                options.weighting_exponent,
                                "; the first two must be positive and the exponent at least 0"));
    VenantBasis basis;
    basis.nodes = patch_nodes(mesh, conductivities, source, around);
    const auto count = static_cast<Eigen::Index>(basis.nodes.size());
    const double a_mm = options.reference_length_mm;
    Eigen::MatrixXd d(3, count); // scaled offsets (x_k - x0) / a
    Eigen::VectorXd weight(count);
    for (Eigen::Index k = 0; k < count; ++k) {
        const Vec3& node = mesh.vertices[basis.nodes[static_cast<std::size_t>(k)]];
        const Vec3 offset = (1 / a_mm) * (node - position_mm);
        d.col(k) << offset[0], offset[1], offset[2];
        weight[k] = std::pow(norm(offset), options.weighting_exponent);
    }
    // Minimise q^T H q, H = Q^T Q + lambda W^2 (Q: traceless second moments, W: weights), subject to
    // C q = t for orders 0 and 1: C = [1; d], t = [0; p / a] (A). Stationarity: H q + C^T mu = 0.
    Eigen::MatrixXd constraints(4, count);
    constraints.row(0).setOnes();
    constraints.bottomRows(3) = d;
    const Eigen::MatrixXd second = traceless_second_moments(d);
    Eigen::MatrixXd system = Eigen::MatrixXd::Zero(count + 4, count + 4);
    system.topLeftCorner(count, count) = second.transpose() * second;
    system.topLeftCorner(count, count).diagonal() += options.regularisation * weight.cwiseAbs2();
    system.topRightCorner(count, 4) = constraints.transpose();
    system.bottomLeftCorner(4, count) = constraints;
    // One right-hand side per unit moment along x, y, z (1 A*m): the currents are linear in p.
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(count + 4, 3);
    const double a_m = a_mm * metres_per_mm;
    for (Eigen::Index i = 0; i < 3; ++i) rhs(count + 1 + i, i) = 1 / a_m;
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(system);
    if (!lu.isInvertible())
        throw AlgorithmError(concat("dipole ", index + 1, ": the Venant moment conditions on its ", count,
                                    " nodes have no unique solution (a flat tet next to the dipole?); use partial ",
                                    "integration or subtraction"));
    const Eigen::MatrixXd solution = lu.solve(rhs);
    for (int axis = 0; axis < 3; ++axis)
        basis.unit_currents_a[static_cast<std::size_t>(axis)].assign(solution.col(axis).data(),
                                                                     solution.col(axis).data() + count);
    return basis;
}

Monopoles venant_monopoles(const TetMesh& mesh, const Conductivities& conductivities, const Dipole& dipole,
                           std::size_t index, const VenantOptions& options)
{
    const std::size_t source = locate_tet(mesh, dipole.position_mm, concat("dipole ", index + 1));
    const std::uint32_t nearest = nearest_corner(mesh, source, dipole.position_mm);
    std::vector<std::uint32_t> around;
    for (std::size_t t = 0; t < mesh.tet_count(); ++t)
        if (std::find(mesh.tets[t].begin(), mesh.tets[t].end(), nearest) != mesh.tets[t].end())
            around.push_back(static_cast<std::uint32_t>(t));
    const VenantBasis basis = venant_basis(mesh, conductivities, dipole.position_mm, index, source, around, options);
    Monopoles monopoles;
    monopoles.nodes = basis.nodes;
    monopoles.currents_a.assign(basis.nodes.size(), 0.0);
    for (std::size_t k = 0; k < basis.nodes.size(); ++k)
        for (std::size_t axis = 0; axis < 3; ++axis)
            monopoles.currents_a[k] += dipole.moment_am[axis] * basis.unit_currents_a[axis][k];
    return monopoles;
}

void add_venant_load(const TetMesh& mesh, const Conductivities& conductivities, const Dipole& dipole, std::size_t index,
                     const VenantOptions& options, Eigen::VectorXd& rhs)
{
    const Monopoles monopoles = venant_monopoles(mesh, conductivities, dipole, index, options);
    for (std::size_t k = 0; k < monopoles.nodes.size(); ++k) rhs[monopoles.nodes[k]] += monopoles.currents_a[k];
}

} // namespace tissuemesh::fem::detail

// The subtraction approach for a current dipole: phi = phi_inf + phi_corr, where phi_inf is the dipole's
// potential in an unbounded medium of the source tissue's conductivity sigma_inf and the correction is the
// P1 solution of
//     integral sigma grad(phi_corr) . grad(v) = - integral (sigma - sigma_inf) grad(phi_inf) . grad(v) dx
//                                             - integral over the boundary sigma_inf (grad(phi_inf) . n) v ds,
// the weak form of div(sigma grad phi_corr) = -div((sigma - sigma_inf) grad(phi_inf)) with the insulated
// outer boundary (sigma d(phi)/dn = 0). The volume term lives only where sigma differs from sigma_inf,
// away from the source, so phi_corr is smooth and P1 resolves it; the singularity is exact.
#pragma once

#include <string>

#include <Eigen/Core>

#include "fem/outer_boundary.h"
#include "fem/solve_potential.h"

namespace tissuemesh::fem::detail {

/// A dipole prepared for subtraction: metres, A*m, S/m.
struct SubtractionSource {
    Vec3 position_m{};
    Vec3 moment_am{};
    double sigma_inf = 0;
};

/// @throws InputError when the dipole is outside the mesh or on a node, or its tissue is anisotropic (names
///         the dipole and the fix: move it, or use partial integration)
SubtractionSource subtraction_source(const TetMesh& mesh, const Conductivities& conductivities, const Dipole& dipole,
                                     std::size_t index);

/// The same for a dipole already located in tet `t`.
SubtractionSource subtraction_source_in(const TetMesh& mesh, const Conductivities& conductivities, const Dipole& dipole,
                                        std::size_t index, std::size_t t);

/// phi_inf (V) at `point_mm`: p . r / (4 pi sigma_inf |r|^3).
double unbounded_potential(const SubtractionSource& source, const Vec3& point_mm);

/// Adds the correction's right-hand side (A) to `rhs`. Volume integrals by a degree-2 rule on tets split
/// into 8 while they are large against their distance to the source (up to 3 times); boundary integrals
/// likewise on triangles. Parallel over tets, summed in tet order (same bytes for any thread count).
void add_subtraction_load(const TetMesh& mesh, const Conductivities& conductivities, const OuterBoundary& boundary,
                          const SubtractionSource& source, Eigen::VectorXd& rhs);

} // namespace tissuemesh::fem::detail

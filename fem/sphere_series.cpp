#include "fem/sphere_series.h"

#include <cmath>
#include <numbers>

#include <Eigen/Dense>

namespace tissuemesh::fem {
namespace {

// Surface value f(1) of the radial function of degree n for a unit source term r^-(n+1) in the innermost
// layer (lengths in units of the outer radius).
double surface_factor(const LayeredSphere& sphere, int n, double source)
{
    const auto layers = static_cast<int>(sphere.radii_mm.size());
    const double outer = sphere.radii_mm.back();
    // Unknowns: A_0, then (A_k, B_k) for k >= 1, at columns 0 and 2k - 1, 2k.
    const int size = 2 * layers - 1;
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(size, size);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(size);
    const double p = n, q = -(n + 1.0);
    const auto a_col = [](int k) { return k == 0 ? 0 : 2 * k - 1; };
    for (int k = 0; k + 1 < layers; ++k) {
        const double a = sphere.radii_mm[k] / outer;
        const double s_in = sphere.sigma_s_per_m[k], s_out = sphere.sigma_s_per_m[k + 1];
        const int row = 2 * k;
        // continuity of f and of sigma f' at r = a
        m(row, a_col(k)) += std::pow(a, p);
        m(row + 1, a_col(k)) += s_in * p * std::pow(a, p - 1);
        if (k > 0) {
            m(row, a_col(k) + 1) += std::pow(a, q);
            m(row + 1, a_col(k) + 1) += s_in * q * std::pow(a, q - 1);
        } else {
            rhs[row] -= source * std::pow(a, q);
            rhs[row + 1] -= s_in * source * q * std::pow(a, q - 1);
        }
        m(row, a_col(k + 1)) -= std::pow(a, p);
        m(row, a_col(k + 1) + 1) -= std::pow(a, q);
        m(row + 1, a_col(k + 1)) -= s_out * p * std::pow(a, p - 1);
        m(row + 1, a_col(k + 1) + 1) -= s_out * q * std::pow(a, q - 1);
    }
    // No radial current at the outer surface r = 1 (in the innermost layer when it is the only one, its
    // r^-(n+1) coefficient being the known source).
    const int last = layers - 1;
    m(size - 1, a_col(last)) = p;
    if (last > 0) m(size - 1, a_col(last) + 1) = q;
    else rhs[size - 1] = -q * source;
    const Eigen::VectorXd x = m.fullPivLu().solve(rhs);
    return x[a_col(last)] + (last > 0 ? x[a_col(last) + 1] : source);
}

} // namespace

std::vector<double> sphere_surface_potentials(const LayeredSphere& sphere, const Vec3& position_mm,
                                              const Vec3& moment_am, const std::vector<Vec3>& surface_points_mm,
                                              int terms)
{
    // Frame: z along the dipole position (or along the surface point for a centred dipole), x along the
    // moment's tangential part. The potential is linear in the moment: radial + tangential parts.
    const double outer = sphere.radii_mm.back();
    const double r0 = norm(position_mm) / outer;
    const Vec3 ez = r0 > 0 ? (1 / norm(position_mm)) * position_mm : Vec3{0, 0, 1};
    const double p_radial = dot(moment_am, ez);
    const Vec3 tangential = moment_am - p_radial * ez;
    const double p_tangential = norm(tangential);
    const Vec3 ex = p_tangential > 0 ? (1 / p_tangential) * tangential : Vec3{1, 0, 0};
    // The radial solution of each degree depends on the layers and the source depth only: once for all points.
    std::vector<double> radial(static_cast<std::size_t>(terms) + 1), tangential_part(radial.size());
    for (int n = 1; n <= terms; ++n) {
        const double factor = surface_factor(sphere, n, 1.0);
        radial[static_cast<std::size_t>(n)] = factor * n * std::pow(r0, n - 1) / sphere.sigma_s_per_m[0];
        tangential_part[static_cast<std::size_t>(n)] = factor * std::pow(r0, n - 1) / sphere.sigma_s_per_m[0];
    }
    const double outer_m = outer * 1e-3;
    std::vector<double> potentials;
    potentials.reserve(surface_points_mm.size());
    for (const Vec3& point : surface_points_mm) {
        const Vec3 u = (1 / norm(point)) * point;
        const double x = dot(u, ez);
        const double sin_theta = std::sqrt(std::max(0.0, 1 - x * x));
        const double cos_phi = sin_theta > 1e-12 ? dot(u, ex) / sin_theta : 0.0;
        // P_n (x) and P_n^1 (x) = sin(theta) P_n'(x) by the three-term recurrences.
        double p_prev = 1, p_cur = x, q_prev = 0, q_cur = sin_theta, sum = 0;
        for (int n = 1; n <= terms; ++n) {
            if (n > 1) {
                const double p_next = ((2 * n - 1) * x * p_cur - (n - 1) * p_prev) / n;
                const double q_next = n == 2 ? 3 * x * sin_theta : ((2 * n - 1) * x * q_cur - n * q_prev) / (n - 1);
                p_prev = p_cur, p_cur = p_next, q_prev = q_cur, q_cur = q_next;
            }
            const auto k = static_cast<std::size_t>(n);
            sum += p_radial * radial[k] * p_cur + p_tangential * tangential_part[k] * q_cur * cos_phi;
        }
        potentials.push_back(sum / (4 * std::numbers::pi * outer_m * outer_m));
    }
    return potentials;
}

double sphere_surface_potential(const LayeredSphere& sphere, const Vec3& position_mm, const Vec3& moment_am,
                                const Vec3& surface_point_mm, int terms)
{
    return sphere_surface_potentials(sphere, position_mm, moment_am, {surface_point_mm}, terms).front();
}

Agreement compare_potentials(std::vector<double> numeric, std::vector<double> analytic)
{
    const auto centre = [](std::vector<double>& v) {
        double mean = 0;
        for (double value : v) mean += value / static_cast<double>(v.size());
        double sum2 = 0;
        for (double& value : v) {
            value -= mean;
            sum2 += value * value;
        }
        return std::sqrt(sum2);
    };
    const double numeric_norm = centre(numeric), analytic_norm = centre(analytic);
    double rdm2 = 0;
    for (std::size_t k = 0; k < numeric.size(); ++k) {
        const double d = numeric[k] / numeric_norm - analytic[k] / analytic_norm;
        rdm2 += d * d;
    }
    return {std::sqrt(rdm2), numeric_norm / analytic_norm};
}

} // namespace tissuemesh::fem

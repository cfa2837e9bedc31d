#include "fem/magnetic_field.h"

#include <algorithm>
#include <array>
#include <cstdint>

#include "core/error.h"
#include "fem/assemble.h"
#include "fem/detail/tet_quadrature.h"
#include "fem/sarvas_field.h"

namespace tissuemesh::fem {
namespace {

constexpr double biot_savart = mu0_t_m_per_a / (4 * 3.14159265358979323846);

// (x - y) / |x - y|^3 (1/m^2) for the coil at x, metres.
Vec3 kernel_at(const Vec3& coil_m, const Vec3& y_m)
{
    const Vec3 r = coil_m - y_m;
    const double r2 = dot(r, r);
    return (1 / (r2 * std::sqrt(r2))) * r;
}

// Adds the kernel of one coil (with `sign`) to `kernel`.
void add_coil(const TetMesh& mesh, const Conductivities& conductivities, const Vec3& coil_mm, const Vec3& normal,
              double sign, const VolumeCurrentOptions& options, std::vector<double>& kernel)
{
    const Vec3 coil_m = metres_per_mm * coil_mm;
    const auto count = static_cast<std::int64_t>(mesh.tet_count());
    std::vector<std::array<double, 4>> loads(mesh.tet_count());
#pragma omp parallel for schedule(dynamic, 4096)
    for (std::int64_t t = 0; t < count; ++t) {
        const auto tet = static_cast<std::size_t>(t);
        const P1Element element = p1_element(mesh, tet);
        std::array<Vec3, 4> corners{};
        for (int k = 0; k < 4; ++k) corners[k] = metres_per_mm * mesh.vertices[mesh.tets[tet][k]];
        const Vec3 integral =
            detail::adaptive_tet_integral(corners, element.volume_m3, coil_m, options.split_ratio, options.max_splits,
                                          [&](const Vec3& y) { return kernel_at(coil_m, y); });
        const Vec3 g_cross_n = cross(integral, normal);
        const Vec3 weighted = multiply(conductivities.of(mesh.tet_labels[tet], tet), g_cross_n); // sigma symmetric
        for (int k = 0; k < 4; ++k) loads[tet][k] = -sign * biot_savart * dot(element.gradients[k], weighted);
    }
    for (std::size_t t = 0; t < mesh.tet_count(); ++t)
        for (int k = 0; k < 4; ++k) kernel[mesh.tets[t][k]] += loads[t][k];
}

} // namespace

double primary_field(const MegSensor& sensor, const Dipole& dipole)
{
    const auto at = [&](const Vec3& coil_mm) {
        const Vec3 r = metres_per_mm * (coil_mm - dipole.position_mm);
        const double length = norm(r);
        return biot_savart * dot(cross(dipole.moment_am, r), sensor.normal) / (length * length * length);
    };
    return at(sensor.position_mm) - (sensor.second_coil_mm ? at(*sensor.second_coil_mm) : 0.0);
}

std::vector<double> volume_current_kernel(const TetMesh& mesh, const Conductivities& conductivities,
                                          const MegSensor& sensor, const VolumeCurrentOptions& options)
{
    std::vector<double> kernel(mesh.vertex_count(), 0.0);
    add_coil(mesh, conductivities, sensor.position_mm, sensor.normal, 1, options, kernel);
    if (sensor.second_coil_mm)
        add_coil(mesh, conductivities, *sensor.second_coil_mm, sensor.normal, -1, options, kernel);
    return kernel;
}

double magnetic_field(const TetMesh& mesh, const Conductivities& conductivities, const std::vector<double>& potential_v,
                      const std::vector<Dipole>& dipoles, const MegSensor& sensor, const VolumeCurrentOptions& options)
{
    if (potential_v.size() != mesh.vertex_count())
        throw InputError(
            concat("magnetic field: ", potential_v.size(), " potentials for ", mesh.vertex_count(), " nodes"));
    const std::vector<double> kernel = volume_current_kernel(mesh, conductivities, sensor, options);
    double field = 0;
    for (std::size_t i = 0; i < kernel.size(); ++i) field += kernel[i] * potential_v[i];
    for (const Dipole& dipole : dipoles) field += primary_field(sensor, dipole);
    return field;
}

} // namespace tissuemesh::fem

#include "fem/sarvas_field.h"

#include <cmath>

#include "fem/assemble.h"

namespace tissuemesh::fem {

Vec3 sarvas_field(const Vec3& sensor_mm, const Vec3& position_mm, const Vec3& moment_am, const Vec3& centre_mm)
{
    const Vec3 r = metres_per_mm * (sensor_mm - centre_mm), r0 = metres_per_mm * (position_mm - centre_mm);
    const Vec3 a = r - r0;
    const double a_length = norm(a), r_length = norm(r);
    const double f = a_length * (r_length * a_length + r_length * r_length - dot(r0, r));
    const Vec3 grad_f = (a_length * a_length / r_length + dot(a, r) / a_length + 2 * a_length + 2 * r_length) * r -
                        (a_length + 2 * r_length + dot(a, r) / a_length) * r0;
    const Vec3 q_cross_r0 = cross(moment_am, r0);
    return (mu0_t_m_per_a / (4 * 3.14159265358979323846 * f * f)) * (f * q_cross_r0 - dot(q_cross_r0, r) * grad_f);
}

} // namespace tissuemesh::fem

#include "volume/detail/tet_quality.h"

#include <algorithm>
#include <cmath>

#include "volume/detail/tetgen_adapter.h"

namespace tissuemesh::volume::detail {
namespace {

constexpr double pi = 3.14159265358979323846;

/// Twice the area vector of the face opposite corner i (any orientation; only its length and direction
/// up to sign are used).
Vec3 face_vector(const TetCorners& p, int i)
{
    const Vec3& a = p[(i + 1) % 4];
    return cross(p[(i + 2) % 4] - a, p[(i + 3) % 4] - a);
}

double six_volume(const TetCorners& p) { return dot(p[1] - p[0], cross(p[2] - p[0], p[3] - p[0])); }

} // namespace

std::array<double, 6> dihedral_sines(const TetCorners& p)
{
    const double v6 = six_volume(p);
    std::array<double, 4> area2; // twice the face areas
    for (int i = 0; i < 4; ++i) area2[i] = norm(face_vector(p, i));
    std::array<double, 6> sines;
    for (int e = 0; e < 6; ++e) {
        const int* c = edge_corners[e];
        const double denominator = area2[c[2]] * area2[c[3]];
        // 6V l / (4 A_f A_g) with the areas doubled: 6V l / (A2_f A2_g).
        sines[e] = denominator > 0 ? v6 * distance(p[c[0]], p[c[1]]) / denominator : 0.0;
    }
    return sines;
}

double min_sine(const TetCorners& p)
{
    const std::array<double, 6> s = dihedral_sines(p);
    return *std::min_element(s.begin(), s.end());
}

std::array<Vec3, 6> dihedral_sine_gradients(const TetCorners& p, int k, const std::array<double, 6>& sines)
{
    // 6V = det[p_a - p_k, p_b - p_k, p_c - p_k] times the parity of the cyclic shift (k, k+1, k+2, k+3), odd
    // for odd k; that determinant is -(p_k - p_a) . n with n the normal of (a, b, c).
    const Vec3& pa = p[(k + 1) % 4];
    const Vec3 opposite = cross(p[(k + 2) % 4] - pa, p[(k + 3) % 4] - pa);
    const Vec3 grad_v6 = (k % 2 == 0 ? -1.0 : 1.0) * opposite;
    // d(2A_i)/dp_k for each face i that holds corner k: n_hat x (r - q) over the face (k, q, r).
    std::array<Vec3, 4> grad_area2{};
    std::array<double, 4> area2{};
    for (int i = 0; i < 4; ++i) {
        const Vec3 fv = face_vector(p, i);
        area2[i] = norm(fv);
        if (i == k || area2[i] == 0) continue;
        int q = -1, r = -1;
        for (int j = 0; j < 4; ++j)
            if (j != i && j != k) (q < 0 ? q : r) = j;
        Vec3 n = cross(p[q] - p[k], p[r] - p[k]);
        const double length = norm(n);
        if (length == 0) continue;
        grad_area2[i] = cross((1.0 / length) * n, p[r] - p[q]);
    }
    std::array<Vec3, 6> gradients{};
    for (int e = 0; e < 6; ++e) {
        const int* c = edge_corners[e];
        const double areas = area2[c[2]] * area2[c[3]];
        if (areas == 0) continue;
        // grad sin = (l / (A2_f A2_g)) grad 6V + sin (grad l / l - grad A2_f / A2_f - grad A2_g / A2_g): no division
        // by the volume, which vanishes for flat tets.
        const double length = distance(p[c[0]], p[c[1]]);
        Vec3 log_part = -1.0 / area2[c[2]] * grad_area2[c[2]] - (1.0 / area2[c[3]]) * grad_area2[c[3]];
        if ((c[0] == k || c[1] == k) && length > 0)
            log_part = log_part + (1.0 / (length * length)) * (p[k] - p[c[0] == k ? c[1] : c[0]]);
        gradients[e] = (length / areas) * grad_v6 + sines[e] * log_part;
    }
    return gradients;
}

bool positive(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) { return exact_side(a, b, c, d) > 0; }

double min_dihedral_deg(const TetCorners& p)
{
    if (six_volume(p) <= 0) return 0;
    // Inward unit normals of the faces; the dihedral angle at the edge two faces share is pi minus the angle
    // between their inward normals.
    std::array<Vec3, 4> normals;
    for (int i = 0; i < 4; ++i) {
        Vec3 n = face_vector(p, i);
        if (dot(n, p[i] - p[(i + 1) % 4]) < 0) n = -1.0 * n;
        const double length = norm(n);
        if (length == 0) return 0;
        normals[i] = (1.0 / length) * n;
    }
    double smallest = 180;
    for (int e = 0; e < 6; ++e) {
        const int* c = edge_corners[e];
        const double cosine = -dot(normals[c[2]], normals[c[3]]);
        smallest = std::min(smallest, std::acos(std::clamp(cosine, -1.0, 1.0)) * 180 / pi);
    }
    return smallest;
}

double sine_of_deg(double angle_deg) { return std::sin(angle_deg * pi / 180); }

} // namespace tissuemesh::volume::detail

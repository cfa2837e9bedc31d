// "ellipsoids": two nested, rotated ellipsoids sampled on an anisotropic, rotated grid.
#include <cmath>
#include <numbers>

#include "image/detail/geometry_primitives.h"
#include "image/detail/phantom_model.h"

namespace tissuemesh::image::detail {
namespace {

constexpr double pi = std::numbers::pi;

/// Rotation by `angle_rad` about the unit `axis` (Rodrigues' formula), row-major.
Mat3 rotation(const Vec3& axis, double angle_rad)
{
    const double c = std::cos(angle_rad), s = std::sin(angle_rad), t = 1 - c;
    const double x = axis[0], y = axis[1], z = axis[2];
    return {t * x * x + c,     t * x * y - s * z, t * x * z + s * y, t * x * y + s * z, t * y * y + c,
            t * y * z - s * x, t * x * z - s * y, t * y * z + s * x, t * z * z + c};
}

/// Tissue 1 inside the outer ellipsoid, tissue 2 inside the inner one; both centred at centre_ with
/// semi-axes along the columns of rotation_ (world = centre + rotation * local).
class Ellipsoids final : public PhantomModel {
public:
    Ellipsoids(Vec3 centre, Mat3 rotation, std::array<double, 3> outer, std::array<double, 3> inner)
        : centre_(centre), rotation_(rotation), axes_{outer, inner}
    {
    }

    Label label_at(const Vec3& p) const override
    {
        const Vec3 q = local(p);
        Label label = 0;
        for (std::size_t k = 0; k < 2 && inside(q, axes_[k]); ++k) label = static_cast<Label>(k + 1);
        return label;
    }
    double distance_to_interface(const Vec3& p, LabelPair pair) const override
    {
        return distance_to_ellipsoid(axes_[pair.from], local(p));
    }
    std::vector<Vec3> sample_interface(LabelPair pair, double spacing_mm) const override
    {
        const auto& e = axes_[pair.from];
        // Thomsen's approximation of the ellipsoid's area (within about 1%) sets the point count.
        const double k = 1.6075;
        const double mean = (std::pow(e[0] * e[1], k) + std::pow(e[0] * e[2], k) + std::pow(e[1] * e[2], k)) / 3;
        const double area = 4 * pi * std::pow(mean, 1 / k);
        std::vector<Vec3> points =
            unit_sphere_points(static_cast<std::size_t>(std::ceil(area / (spacing_mm * spacing_mm))));
        for (Vec3& p : points) p = centre_ + multiply(rotation_, Vec3{e[0] * p[0], e[1] * p[1], e[2] * p[2]});
        return points;
    }
    std::vector<LabelPair> interfaces() const override { return {{0, 1}, {1, 2}}; }
    double tissue_volume_mm3(Label label) const override
    {
        const auto volume = [](const std::array<double, 3>& e) { return 4.0 / 3.0 * pi * e[0] * e[1] * e[2]; };
        if (label == 1) return volume(axes_[0]) - volume(axes_[1]);
        return label == 2 ? volume(axes_[1]) : 0;
    }
    nlohmann::json primitives() const override
    {
        nlohmann::json list = nlohmann::json::array();
        for (std::size_t k = 0; k < 2; ++k)
            list.push_back({{"type", "ellipsoid"},
                            {"centre", to_json(centre_)},
                            {"semi_axes", {axes_[k][0], axes_[k][1], axes_[k][2]}},
                            {"rotation_row_major", rotation_},
                            {"label", k + 1}});
        return {{"rule", "world = centre + rotation * local; a point takes the label of the last "
                         "ellipsoid containing it"},
                {"shapes", list}};
    }

private:
    Vec3 local(const Vec3& p) const { return multiply(transpose(rotation_), p - centre_); }
    static bool inside(const Vec3& q, const std::array<double, 3>& e)
    {
        double sum = 0;
        for (int a = 0; a < 3; ++a) sum += (q[a] / e[a]) * (q[a] / e[a]);
        return sum <= 1;
    }

    Vec3 centre_;
    Mat3 rotation_;
    std::array<std::array<double, 3>, 2> axes_;
};

} // namespace

PhantomSetup make_ellipsoids(double voxel_mm)
{
    const Vec3 centre{5.5, -3.25, 12.0};
    const double skew = 1 / std::sqrt(14.0); // the unit axis (1, 2, 3) / sqrt(14)
    const Mat3 shape_rotation = rotation({skew, 2 * skew, 3 * skew}, 35 * pi / 180);
    auto model = std::make_shared<Ellipsoids>(centre, shape_rotation, std::array<double, 3>{45, 35, 25},
                                              std::array<double, 3>{33, 22, 15});
    model->names = {{0, "background"}, {1, "outer"}, {2, "inner"}};
    // The grid is rotated too (25 degrees about z) and anisotropic; a ball of 45 mm holds the phantom.
    const Vec3 spacing{voxel_mm, voxel_mm, 1.5 * voxel_mm};
    const Dims dims{voxels_for(45, spacing[0]), voxels_for(45, spacing[1]), voxels_for(45, spacing[2])};
    return {model, centred_grid(dims, spacing, centre, rotation({0, 0, 1}, 25 * pi / 180))};
}

} // namespace tissuemesh::image::detail

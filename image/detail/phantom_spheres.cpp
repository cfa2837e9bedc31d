// Sphere phantoms: "spheres4" (the 4-shell EEG head), "thin" (a one-voxel shell) and "junction"
// (a shell around a ball split by a plane: three tissues meet along a circle).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "image/detail/geometry_primitives.h"
#include "image/detail/phantom_model.h"

namespace tissuemesh::image::detail {
namespace {

constexpr double pi = std::numbers::pi;

double ball_volume(double radius) { return 4.0 / 3.0 * pi * radius * radius * radius; }

std::vector<Vec3> sphere_points(const Vec3& centre, double radius, double spacing_mm)
{
    const double area = 4 * pi * radius * radius;
    std::vector<Vec3> points =
        unit_sphere_points(static_cast<std::size_t>(std::ceil(area / (spacing_mm * spacing_mm))));
    for (Vec3& p : points) p = centre + radius * p;
    return points;
}

/// Concentric spheres: tissue labels[k] fills radii_[k+1] < r <= radii_[k] (radii descending).
class NestedSpheres final : public PhantomModel {
public:
    NestedSpheres(Vec3 centre, std::vector<double> radii) : centre_(centre), radii_(std::move(radii)) {}

    Label label_at(const Vec3& p) const override
    {
        const double r = distance(p, centre_);
        Label label = 0;
        for (std::size_t k = 0; k < radii_.size() && r <= radii_[k]; ++k) label = static_cast<Label>(k + 1);
        return label;
    }
    double distance_to_interface(const Vec3& p, LabelPair pair) const override
    {
        return distance_to_sphere(p, centre_, radii_[pair.from]); // interface (k, k+1) is sphere k
    }
    std::vector<Vec3> sample_interface(LabelPair pair, double spacing_mm) const override
    {
        return sphere_points(centre_, radii_[pair.from], spacing_mm);
    }
    std::vector<LabelPair> interfaces() const override
    {
        std::vector<LabelPair> pairs;
        for (std::size_t k = 0; k < radii_.size(); ++k)
            pairs.push_back({static_cast<Label>(k), static_cast<Label>(k + 1)});
        return pairs;
    }
    double tissue_volume_mm3(Label label) const override
    {
        if (label == 0 || label > radii_.size()) return 0;
        const double inner = label < radii_.size() ? ball_volume(radii_[label]) : 0;
        return ball_volume(radii_[label - 1]) - inner;
    }
    nlohmann::json primitives() const override
    {
        nlohmann::json list = nlohmann::json::array();
        for (std::size_t k = 0; k < radii_.size(); ++k)
            list.push_back({{"type", "ball"}, {"centre", to_json(centre_)}, {"radius", radii_[k]}, {"label", k + 1}});
        return {{"rule", "a point takes the label of the last (innermost) ball containing it"}, {"shapes", list}};
    }

private:
    Vec3 centre_;
    std::vector<double> radii_;
};

/// A shell (1) between radii inner_ and outer_, around a ball split by the plane through the centre
/// with unit normal normal_: tissue 2 where dot(p - c, n) < 0, tissue 3 on the other side.
class Junction final : public PhantomModel {
public:
    Junction(Vec3 centre, double outer, double inner, Vec3 normal)
        : centre_(centre), outer_(outer), inner_(inner), normal_(normal)
    {
    }

    Label label_at(const Vec3& p) const override
    {
        const double r = distance(p, centre_);
        if (r > outer_) return 0;
        if (r > inner_) return 1;
        return dot(p - centre_, normal_) < 0 ? 2 : 3;
    }
    double distance_to_interface(const Vec3& p, LabelPair pair) const override
    {
        if (pair.from == 0) return distance_to_sphere(p, centre_, outer_);
        if (pair.from == 2) return distance_to_disk(p, centre_, inner_, normal_);
        const Vec3 side = pair.to == 2 ? normal_ : -1.0 * normal_; // 1|2 is the half with dot <= 0
        return distance_to_hemisphere(p, centre_, inner_, side);
    }
    std::vector<Vec3> sample_interface(LabelPair pair, double spacing_mm) const override
    {
        if (pair.from == 0) return sphere_points(centre_, outer_, spacing_mm);
        if (pair.from == 2) return disk_points(spacing_mm);
        const double sign = pair.to == 2 ? -1.0 : 1.0;
        std::vector<Vec3> points;
        for (const Vec3& p : sphere_points(centre_, inner_, spacing_mm))
            if (sign * dot(p - centre_, normal_) >= 0) points.push_back(p);
        return points;
    }
    std::vector<LabelPair> interfaces() const override { return {{0, 1}, {1, 2}, {1, 3}, {2, 3}}; }
    double tissue_volume_mm3(Label label) const override
    {
        if (label == 1) return ball_volume(outer_) - ball_volume(inner_);
        if (label == 2 || label == 3) return ball_volume(inner_) / 2;
        return 0;
    }
    nlohmann::json primitives() const override
    {
        return {{"rule", "tissue 1 for inner_radius < |p - centre| <= outer_radius; inside inner_radius, "
                         "tissue 2 where dot(p - centre, normal) < 0, else tissue 3"},
                {"shapes",
                 {{{"type", "split_shell"},
                   {"centre", to_json(centre_)},
                   {"outer_radius", outer_},
                   {"inner_radius", inner_},
                   {"normal", to_json(normal_)}}}}};
    }

private:
    /// Rings of points on the disk, about spacing_mm apart, the rim included.
    std::vector<Vec3> disk_points(double spacing_mm) const
    {
        const Vec3 helper = std::abs(normal_[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
        Vec3 u = cross(normal_, helper);
        u = (1.0 / norm(u)) * u;
        const Vec3 v = cross(normal_, u);
        std::vector<Vec3> points{centre_};
        const auto rings = static_cast<std::size_t>(std::ceil(inner_ / spacing_mm));
        for (std::size_t ring = 1; ring <= rings; ++ring) {
            const double r = inner_ * static_cast<double>(ring) / static_cast<double>(rings);
            const auto count = std::max<std::size_t>(6, static_cast<std::size_t>(std::ceil(2 * pi * r / spacing_mm)));
            for (std::size_t k = 0; k < count; ++k) {
                const double angle = 2 * pi * static_cast<double>(k) / static_cast<double>(count);
                points.push_back(centre_ + r * std::cos(angle) * u + r * std::sin(angle) * v);
            }
        }
        return points;
    }

    Vec3 centre_;
    double outer_, inner_;
    Vec3 normal_;
};

Dims cube_dims(double half_extent_mm, double voxel_mm)
{
    const std::size_t n = voxels_for(half_extent_mm, voxel_mm);
    return {n, n, n};
}

} // namespace

PhantomSetup make_spheres4(double voxel_mm)
{
    auto model = std::make_shared<NestedSpheres>(Vec3{0, 0, 0}, std::vector<double>{92, 86, 80, 78});
    model->names = {{0, "background"}, {1, "scalp"}, {2, "skull"}, {3, "csf"}, {4, "brain"}};
    return {model, centred_grid(cube_dims(92, voxel_mm), {voxel_mm, voxel_mm, voxel_mm}, {0, 0, 0})};
}

PhantomSetup make_thin(double voxel_mm)
{
    // The shell is exactly one voxel thick whatever the voxel size.
    const double ball = 20;
    auto model = std::make_shared<NestedSpheres>(Vec3{0, 0, 0}, std::vector<double>{ball + voxel_mm, ball});
    model->names = {{0, "background"}, {1, "shell"}, {2, "ball"}};
    return {model, centred_grid(cube_dims(ball + voxel_mm, voxel_mm), {voxel_mm, voxel_mm, voxel_mm}, {0, 0, 0})};
}

PhantomSetup make_junction(double voxel_mm)
{
    // The plane is tilted so that no axis-aligned row of voxel centres lies in it.
    Vec3 normal{0.3, 0.2, 1.0};
    normal = (1.0 / norm(normal)) * normal;
    auto model = std::make_shared<Junction>(Vec3{0, 0, 0}, 40.0, 30.0, normal);
    model->names = {{0, "background"}, {1, "shell"}, {2, "lower_half"}, {3, "upper_half"}};
    return {model, centred_grid(cube_dims(40, voxel_mm), {voxel_mm, voxel_mm, voxel_mm}, {0, 0, 0})};
}

} // namespace tissuemesh::image::detail

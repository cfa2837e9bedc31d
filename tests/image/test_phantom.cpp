#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <random>

#include "core/error.h"
#include "image/detail/geometry_primitives.h"
#include "image/phantom.h"

namespace tissuemesh::image {
namespace {

const std::vector<std::string> all_phantoms{"spheres4", "junction", "thin", "boxes", "ellipsoids"};

Vec3 centre_of(const LabelImage& image, std::size_t i, std::size_t j, std::size_t k)
{
    return image.index_to_world({static_cast<double>(i), static_cast<double>(j), static_cast<double>(k)});
}

TEST(Phantom, ImageIsTheGeometrySampledAtVoxelCentres)
{
    for (const std::string& name : all_phantoms) {
        const Phantom phantom = make_phantom(name, {.voxel_mm = 2.0});
        const LabelImage& image = phantom.image;
        std::size_t mismatches = 0;
        for (std::size_t k = 0; k < image.dims()[2]; ++k)
            for (std::size_t j = 0; j < image.dims()[1]; ++j)
                for (std::size_t i = 0; i < image.dims()[0]; ++i)
                    mismatches += image.at(i, j, k) != phantom.geometry.label_at(centre_of(image, i, j, k));
        EXPECT_EQ(mismatches, 0u) << name;
        EXPECT_EQ(image.names(), phantom.geometry.names()) << name;
        EXPECT_EQ(phantom.geometry.name(), name);
    }
}

TEST(Phantom, KeepsTwoVoxelsOfBackgroundAtTheBorder)
{
    for (const std::string& name : all_phantoms) {
        const Phantom phantom = make_phantom(name, {.voxel_mm = 1.7});
        const Dims& d = phantom.image.dims();
        std::size_t tissue_near_border = 0;
        for (std::size_t k = 0; k < d[2]; ++k)
            for (std::size_t j = 0; j < d[1]; ++j)
                for (std::size_t i = 0; i < d[0]; ++i) {
                    const bool near = std::min({i, j, k}) < 2 || i + 2 >= d[0] || j + 2 >= d[1] || k + 2 >= d[2];
                    tissue_near_border += near && phantom.image.at(i, j, k) != 0;
                }
        EXPECT_EQ(tissue_near_border, 0u) << name;
    }
}

TEST(Phantom, VoxelVolumesMatchExactVolumes)
{
    // Point sampling counts the voxel centres inside each tissue; for these smooth or grid-aligned
    // shapes the count times the voxel volume deviates from the exact volume by far less than one voxel
    // layer over the surface. 2% for tissues at least 3 voxels thick; 8% for the one-voxel shells
    // (thin's shell, spheres4's 2 mm CSF at 2 mm), whose counts hinge on a single layer.
    for (const std::string& name : all_phantoms) {
        const Phantom phantom = make_phantom(name, {.voxel_mm = 2.0});
        const auto counts = count_labels(phantom.image);
        for (const Label label : phantom.geometry.tissues()) {
            const double exact = phantom.geometry.volume_mm3(label);
            const double sampled = static_cast<double>(counts.at(label)) * phantom.image.voxel_volume_mm3();
            const bool one_voxel = (name == "thin" && label == 1) || (name == "spheres4" && label == 3);
            EXPECT_NEAR(sampled / exact, 1.0, one_voxel ? 0.08 : 0.02) << name << " tissue " << label;
        }
        // The background volume is the rest of the image domain: the totals must agree exactly.
        const double total = static_cast<double>(phantom.image.voxel_count()) * phantom.image.voxel_volume_mm3();
        double exact_total = 0;
        for (const auto& [label, tissue] : phantom.geometry.names()) exact_total += phantom.geometry.volume_mm3(label);
        EXPECT_NEAR(exact_total, total, 1e-6 * total) << name;
    }
}

TEST(Phantom, Spheres4HasTheStandardRadiiAndSize)
{
    const Phantom phantom = make_phantom("spheres4", {});
    EXPECT_EQ(phantom.image.dims(), (Dims{188, 188, 188}));
    const auto& g = phantom.geometry;
    EXPECT_EQ(g.names().at(1), "scalp");
    EXPECT_EQ(g.names().at(4), "brain");
    const std::vector<double> radii{92, 86, 80, 78};
    for (Label k = 0; k < 4; ++k) {
        EXPECT_NEAR(g.distance_to_interface({0, 0, 0}, {k, static_cast<Label>(k + 1)}), radii[k], 1e-12);
        EXPECT_NEAR(g.distance_to_interface({0, 100, 0}, {static_cast<Label>(k + 1), k}), 100 - radii[k], 1e-12);
    }
    EXPECT_EQ(g.label_at({0, 0, 91.9}), 1);
    EXPECT_EQ(g.label_at({0, 0, 92.1}), 0);
    EXPECT_EQ(g.label_at({79, 0, 0}), 3);
    EXPECT_NEAR(g.volume_mm3(4), 4.0 / 3.0 * M_PI * 78 * 78 * 78, 1e-6);
}

TEST(Phantom, SampledInterfacePointsLieOnTheInterfaceBetweenItsTissues)
{
    for (const std::string& name : all_phantoms) {
        const Phantom phantom = make_phantom(name, {.voxel_mm = 2.0});
        const auto& g = phantom.geometry;
        for (const LabelPair& pair : g.interfaces()) {
            const auto points = g.sample_interface(pair, 3.0);
            ASSERT_GT(points.size(), 10u) << name;
            for (const Vec3& p : points) {
                // Exact up to rounding of the sample coordinates (|p| < 100 mm).
                ASSERT_LT(g.distance_to_interface(p, pair), 1e-9) << name << " " << pair.from << "|" << pair.to;
                ASSERT_LT(g.distance_to_interface(p, {pair.to, pair.from}), 1e-9);
                // Both tissues are found within 1e-6 mm of the point (26 directions: on the boxes'
                // edges the second tissue lies diagonally).
                bool seen_from = false, seen_to = false;
                for (int code = 0; code < 27; ++code) {
                    const Vec3 q = p + 1e-6 * Vec3{code % 3 - 1.0, code / 3 % 3 - 1.0, code / 9 - 1.0};
                    seen_from |= g.label_at(q) == pair.from;
                    seen_to |= g.label_at(q) == pair.to;
                }
                ASSERT_TRUE(seen_from && seen_to) << name << " " << pair.from << "|" << pair.to;
            }
        }
    }
}

TEST(Phantom, DistanceIsTheDistanceToTheSampledInterface)
{
    // Dense samples lie on the interface, so the exact distance can never exceed their nearest one, and
    // the nearest sample is at most about one sample spacing further than the exact closest point.
    std::mt19937 random(7);
    std::uniform_real_distribution<double> coordinate(-60, 60);
    for (const std::string& name : all_phantoms) {
        const Phantom phantom = make_phantom(name, {.voxel_mm = 2.0});
        const auto& g = phantom.geometry;
        for (const LabelPair& pair : g.interfaces()) {
            const double spacing = 0.5;
            const auto samples = g.sample_interface(pair, spacing);
            for (int trial = 0; trial < 40; ++trial) {
                const Vec3 p{coordinate(random), coordinate(random), coordinate(random)};
                double nearest = INFINITY;
                for (const Vec3& s : samples) nearest = std::min(nearest, distance(p, s));
                const double exact = g.distance_to_interface(p, pair);
                EXPECT_LE(exact, nearest + 1e-9) << name << " " << pair.from << "|" << pair.to;
                EXPECT_LE(nearest, exact + 1.5 * spacing) << name << " " << pair.from << "|" << pair.to;
            }
        }
    }
}

TEST(Phantom, JunctionDistancesToDiskAndHalfSpheres)
{
    const Phantom phantom = make_phantom("junction", {.voxel_mm = 2.0});
    const auto& g = phantom.geometry;
    const Vec3 n = Vec3{0.3, 0.2, 1.0} * (1 / std::sqrt(0.09 + 0.04 + 1.0));
    const Vec3 above = 10.0 * n; // inside tissue 3, 10 mm from the splitting disk
    EXPECT_EQ(g.label_at(above), 3);
    EXPECT_EQ(g.label_at(-1.0 * above), 2);
    EXPECT_NEAR(g.distance_to_interface(above, {2, 3}), 10, 1e-12);
    EXPECT_NEAR(g.distance_to_interface(above, {1, 3}), 20, 1e-12);                     // radially out
    EXPECT_NEAR(g.distance_to_interface(above, {1, 2}), std::hypot(30.0, 10.0), 1e-12); // to the rim
    const Vec3 in_plane = cross(n, {1, 0, 0}) * (50 / norm(cross(n, {1, 0, 0})));
    EXPECT_NEAR(g.distance_to_interface(in_plane, {2, 3}), 20, 1e-12);
    EXPECT_NEAR(g.distance_to_interface(in_plane, {0, 1}), 10, 1e-12);
}

TEST(Phantom, ThinShellIsOneVoxelThick)
{
    for (const double h : {0.7, 1.0, 2.0}) {
        const Phantom phantom = make_phantom("thin", {.voxel_mm = h});
        const LabelImage& image = phantom.image;
        const std::size_t mid = image.dims()[0] / 2; // the rows nearest the centre, h/2 off it
        for (int axis = 0; axis < 3; ++axis) {
            std::size_t shell = 0;
            for (std::size_t t = 0; t < image.dims()[0]; ++t) {
                std::array<std::size_t, 3> index{mid, mid, mid};
                index[axis] = t;
                shell += image.at(index[0], index[1], index[2]) == 1;
            }
            EXPECT_EQ(shell, 2u) << "voxel " << h << " mm, axis " << axis; // one voxel on each side
        }
        EXPECT_NEAR(phantom.geometry.distance_to_interface({0, 0, 0}, {0, 1}) -
                        phantom.geometry.distance_to_interface({0, 0, 0}, {1, 2}),
                    h, 1e-12);
    }
}

TEST(Phantom, BoxFacesAvoidVoxelCentres)
{
    // Every voxel centre is at least 0.3 voxel (minus rounding) from every box face, so no voxel's
    // classification depends on the rounding of its centre.
    const double h = 1.3;
    const Phantom phantom = make_phantom("boxes", {.voxel_mm = h});
    const auto& image = phantom.image;
    double closest = INFINITY;
    for (std::size_t k = 0; k < image.dims()[2]; k += 1)
        for (std::size_t j = 0; j < image.dims()[1]; j += 3)
            for (std::size_t i = 0; i < image.dims()[0]; i += 3)
                for (const LabelPair& pair : phantom.geometry.interfaces())
                    closest =
                        std::min(closest, phantom.geometry.distance_to_interface(centre_of(image, i, j, k), pair));
    EXPECT_GT(closest, 0.3 * h - 1e-9);
    EXPECT_LT(closest, 0.3 * h + 1e-9); // and the closest face is exactly 0.3 voxel away
}

TEST(Phantom, EllipsoidsUseAnisotropicRotatedGrid)
{
    const Phantom phantom = make_phantom("ellipsoids", {.voxel_mm = 1.0});
    EXPECT_DOUBLE_EQ(phantom.image.spacing_mm()[2], 1.5);
    EXPECT_NE(phantom.image.direction(), identity_matrix());
    EXPECT_NE(phantom.image.origin_mm(), (Vec3{0, 0, 0}));
}

/// Brute-force distance to the ellipsoid: a parameter grid, refined around the best cell five times.
double brute_force_ellipsoid(const std::array<double, 3>& e, const Vec3& p)
{
    const auto at = [&](double theta, double phi) {
        const Vec3 x{e[0] * std::sin(theta) * std::cos(phi), e[1] * std::sin(theta) * std::sin(phi),
                     e[2] * std::cos(theta)};
        return distance(x, p);
    };
    double best = INFINITY, best_theta = 0, best_phi = 0;
    double d_theta = M_PI / 400, d_phi = 2 * M_PI / 800;
    for (int a = 0; a <= 400; ++a)
        for (int b = 0; b < 800; ++b)
            if (const double d = at(a * d_theta, b * d_phi); d < best)
                best = d, best_theta = a * d_theta, best_phi = b * d_phi;
    for (int round = 0; round < 8; ++round) {
        const double t0 = best_theta, p0 = best_phi;
        for (int a = -20; a <= 20; ++a)
            for (int b = -20; b <= 20; ++b)
                if (const double d = at(t0 + a * d_theta / 10, p0 + b * d_phi / 10); d < best)
                    best = d, best_theta = t0 + a * d_theta / 10, best_phi = p0 + b * d_phi / 10;
        d_theta /= 10, d_phi /= 10;
    }
    return best;
}

TEST(Phantom, EllipsoidDistanceMatchesBruteForce)
{
    const std::array<double, 3> e{45, 35, 25};
    std::vector<Vec3> points{{0, 0, 0},  {10, 0, 0},  {0, 10, 0},   {0, 0, 10},    {44, 0, 0}, {60, 0, 0},
                             {0, 0, 30}, {20, 15, 0}, {30, -10, 5}, {-50, 40, 30}, {45, 0, 0}, {5, 5, 24}};
    std::mt19937 random(11);
    std::uniform_real_distribution<double> coordinate(-60, 60);
    for (int n = 0; n < 20; ++n) points.push_back({coordinate(random), coordinate(random), coordinate(random)});
    for (const Vec3& p : points) {
        const double exact = detail::distance_to_ellipsoid(e, p);
        // The refined grid reaches ~1e-9 rad; the distance is stationary there, so 1e-6 mm is ample.
        EXPECT_NEAR(exact, brute_force_ellipsoid(e, p), 1e-6) << p[0] << " " << p[1] << " " << p[2];
    }
    // The degenerate branch: from (10, 0, 0) the nearest point is off the longest axis' plane.
    EXPECT_LT(detail::distance_to_ellipsoid(e, {10, 0, 0}), 25.0 - 0.5);
}

TEST(Phantom, RejectsUnknownNamesPairsAndVoxelSizes)
{
    try {
        make_phantom("sphere", {});
        FAIL() << "unknown phantom accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("unknown phantom 'sphere'; choose one of: spheres4"), std::string::npos);
    }
    EXPECT_THROW(make_phantom("thin", {.voxel_mm = 0}), InputError);
    EXPECT_THROW(make_phantom("thin", {.voxel_mm = -1}), InputError);
    EXPECT_THROW(make_phantom("thin", {.voxel_mm = NAN}), InputError);
    const Phantom phantom = make_phantom("spheres4", {.voxel_mm = 4});
    EXPECT_THROW(phantom.geometry.distance_to_interface({0, 0, 0}, {1, 3}), InputError);
    EXPECT_THROW(phantom.geometry.sample_interface({1, 2}, 0), InputError);
    EXPECT_EQ(phantom_names().size(), all_phantoms.size());
}

TEST(Phantom, GeometryJsonDescribesTissuesInterfacesAndVolumes)
{
    const Phantom phantom = make_phantom("junction", {.voxel_mm = 2});
    const auto document = nlohmann::json::parse(phantom.geometry.to_json());
    EXPECT_EQ(document.at("phantom"), "junction");
    EXPECT_EQ(document.at("labels").at("1"), "shell");
    EXPECT_EQ(document.at("interfaces").size(), 4u);
    EXPECT_NEAR(document.at("volume_mm3").at("2").get<double>(), 2.0 / 3.0 * M_PI * 27000, 1e-6);
    EXPECT_EQ(document.at("geometry").at("shapes").at(0).at("outer_radius"), 40.0);
}

} // namespace
} // namespace tissuemesh::image

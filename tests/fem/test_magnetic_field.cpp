// MEG: Sarvas' formula checked against what any field outside a spherically symmetric conductor must be, and
// lead fields on the 4-shell head against the 4-shell series (EEG) and Sarvas (MEG).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "fem/lead_field.h"
#include "fem/magnetic_field.h"
#include "fem/sarvas_field.h"
#include "fem/sphere_series.h"
#include "fem_meshes.h"

namespace tissuemesh::fem {
namespace {

Vec3 unit(const Vec3& v) { return (1 / norm(v)) * v; }

// Outside the conductor B is the gradient of a harmonic potential, so it is free of divergence and curl, and
// its radial part is the primary current's alone (the volume currents of a spherically symmetric conductor
// have none). Together these fix B: a typo in F or grad F breaks one of them. Central differences of 1e-3 mm
// at 30-60 mm from the dipole: their error is about 1e-9 of |B| / mm, the bounds 1e-6.
TEST(SarvasField, IsDivergenceAndCurlFreeWithThePrimaryRadialPart)
{
    const Vec3 position{10, -20, 45}, moment{1e-8, 2e-8, -0.5e-8};
    for (const Vec3& sensor : {Vec3{0, 0, 102}, Vec3{-60, 60, 55}, Vec3{95, -20, 30}, Vec3{5, -100, 20}}) {
        const Vec3 b = sarvas_field(sensor, position, moment);
        const MegSensor radial{sensor, unit(sensor), std::nullopt, ""};
        EXPECT_NEAR(dot(b, unit(sensor)), primary_field(radial, {position, moment}), 1e-12 * norm(b));
        const double h = 1e-3;
        double divergence = 0;
        Vec3 curl{0, 0, 0};
        std::array<Vec3, 3> derivative{}; // d B / d x_a
        for (int a = 0; a < 3; ++a) {
            Vec3 step{0, 0, 0};
            step[static_cast<std::size_t>(a)] = h;
            derivative[static_cast<std::size_t>(a)] = (0.5 / h) * (sarvas_field(sensor + step, position, moment) -
                                                                   sarvas_field(sensor - step, position, moment));
            divergence += derivative[static_cast<std::size_t>(a)][static_cast<std::size_t>(a)];
        }
        curl = {derivative[1][2] - derivative[2][1], derivative[2][0] - derivative[0][2],
                derivative[0][1] - derivative[1][0]};
        const double scale = norm(derivative[0]) + norm(derivative[1]) + norm(derivative[2]);
        EXPECT_LT(std::abs(divergence), 1e-6 * scale);
        EXPECT_LT(norm(curl), 1e-6 * scale);
    }
    // A radial dipole has no field outside (q x r0 = 0).
    EXPECT_EQ(norm(sarvas_field({30, 40, 90}, {0, 0, 50}, {0, 0, 1e-8})), 0.0);
}

// Constants carry no current: the kernel sums to zero (to round-off), and it is linear in the coil normal.
TEST(MagneticField, VolumeCurrentKernelSumsToZero)
{
    const TetMesh mesh = testing::four_shell_head(2, 100.0);
    const Conductivities sigma = resolve_conductivities(mesh, {});
    const std::vector<double> kernel =
        volume_current_kernel(mesh, sigma, {{0, 20, 100}, {0, 0.6, 0.8}, std::nullopt, ""});
    double sum = 0, size = 0;
    for (const double value : kernel) sum += value, size += std::abs(value);
    EXPECT_LT(std::abs(sum), 1e-12 * size);
    const std::vector<double> y = volume_current_kernel(mesh, sigma, {{0, 20, 100}, {0, 1, 0}, std::nullopt, ""});
    const std::vector<double> z = volume_current_kernel(mesh, sigma, {{0, 20, 100}, {0, 0, 1}, std::nullopt, ""});
    for (std::size_t i = 0; i < kernel.size(); ++i) EXPECT_NEAR(kernel[i], 0.6 * y[i] + 0.8 * z[i], 1e-12 * size);
}

double median(std::vector<double> values)
{
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
}

// Lead fields of 24 free sources at eccentricities 0.2-0.9 of the 78 mm brain (random directions) on the
// 62 k-node icosphere head of test_four_shell.cpp, Venant: EEG at 32 electrodes against the 4-shell series
// at the projected electrode positions (pushed onto the exact sphere), MEG at 30 radial and 10 tangential
// magnetometers 10 mm off the scalp against Sarvas. RDM (0..2) over the sensors per column, EEG average
// referenced. Measured (72 columns): EEG median RDM 0.0032, worst 0.0137, median |MAG - 1| 0.0033; MEG median
// RDM 0.0034, worst 0.0142. The bounds are the (medians 1% and 2%) and the measured worst plus a margin.
TEST(LeadField, FourShellHeadAgreesWithTheSeriesAndSarvas)
{
    const TetMesh mesh = testing::four_shell_head(4, 10.0);
    const Conductivities sigma = resolve_conductivities(mesh, {});
    std::vector<EegElectrode> electrodes;
    const double golden = std::numbers::pi * (3 - std::sqrt(5.0));
    for (int k = 0; k < 32; ++k) { // the upper part of the head, as a cap covers it
        const double z = 1 - (k + 0.5) / 32 * 1.3, r = std::sqrt(1 - z * z);
        electrodes.push_back({92.5 * Vec3{r * std::cos(golden * k), r * std::sin(golden * k), z}, ""});
    }
    std::vector<MegSensor> meg;
    for (int k = 0; k < 40; ++k) {
        const double z = 1 - (k + 0.5) / 40 * 1.2, r = std::sqrt(1 - z * z);
        const Vec3 direction{r * std::cos(golden * k), r * std::sin(golden * k), z};
        const Vec3 tangent = unit(cross(direction, Vec3{0.3, -0.4, 0.866}));
        meg.push_back({102 * direction, k < 30 ? direction : tangent, std::nullopt, ""});
    }
    std::mt19937 random(29);
    std::uniform_real_distribution<double> uniform(-1, 1);
    std::vector<LeadFieldSource> sources;
    for (int s = 0; s < 24; ++s) {
        Vec3 direction{uniform(random), uniform(random), std::abs(uniform(random)) + 0.2};
        sources.push_back({78 * (0.2 + 0.7 * s / 23.0) * unit(direction), std::nullopt, ""});
    }
    LeadFieldReport report;
    const LeadFields fields = compute_lead_fields(mesh, sigma, electrodes, meg, sources, {}, {}, &report);
    std::vector<Vec3> on_sphere;
    for (const SurfacePoint& point : report.electrodes) on_sphere.push_back(92 * unit(point.position_mm));
    std::vector<double> eeg_rdm, eeg_mag, meg_rdm, primary_only_rdm;
    for (std::size_t s = 0; s < sources.size(); ++s)
        for (int axis = 0; axis < 3; ++axis) {
            Vec3 moment{0, 0, 0};
            moment[static_cast<std::size_t>(axis)] = 1;
            const auto column = static_cast<Eigen::Index>(3 * s) + axis;
            std::vector<double> eeg(32);
            for (Eigen::Index e = 0; e < 32; ++e) eeg[static_cast<std::size_t>(e)] = fields.eeg(e, column);
            const Agreement a = compare_potentials(
                eeg, sphere_surface_potentials(testing::four_shell_series, sources[s].position_mm, moment, on_sphere));
            eeg_rdm.push_back(a.rdm);
            eeg_mag.push_back(std::abs(a.mag - 1));
            Eigen::VectorXd fe(40), exact(40);
            for (Eigen::Index j = 0; j < 40; ++j) {
                fe[j] = fields.meg(j, column);
                exact[j] =
                    dot(sarvas_field(meg[static_cast<std::size_t>(j)].position_mm, sources[s].position_mm, moment),
                        meg[static_cast<std::size_t>(j)].normal);
            }
            meg_rdm.push_back((fe / fe.norm() - exact / exact.norm()).norm());
            // The tangential magnetometers see the volume currents: without them the field is far off.
            Eigen::VectorXd primary(10), tangential = exact.tail(10);
            for (Eigen::Index j = 0; j < 10; ++j)
                primary[j] = primary_field(meg[static_cast<std::size_t>(30 + j)], {sources[s].position_mm, moment});
            primary_only_rdm.push_back((primary / primary.norm() - tangential / tangential.norm()).norm());
        }
    std::printf(
        "[lead field] 4-shell head, %zu nodes, %zu columns: EEG median RDM %.4f, worst %.4f, median |MAG - 1| %.4f; "
        "MEG median RDM %.4f, worst %.4f\n",
        mesh.vertex_count(), report.columns, median(eeg_rdm), *std::max_element(eeg_rdm.begin(), eeg_rdm.end()),
        median(eeg_mag), median(meg_rdm), *std::max_element(meg_rdm.begin(), meg_rdm.end()));
    EXPECT_LT(median(eeg_rdm), 0.01);
    EXPECT_LT(*std::max_element(eeg_rdm.begin(), eeg_rdm.end()), 0.03);
    EXPECT_LT(median(eeg_mag), 0.02);
    EXPECT_LT(median(meg_rdm), 0.01);
    std::printf("[lead field] tangential magnetometers, primary field alone: median RDM %.3f\n",
                median(primary_only_rdm));
    EXPECT_GT(median(primary_only_rdm), 10 * median(meg_rdm));
    EXPECT_LT(*std::max_element(meg_rdm.begin(), meg_rdm.end()), 0.03);
}

} // namespace
} // namespace tissuemesh::fem

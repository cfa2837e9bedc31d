// Conductivity tables and the P1 stiffness matrix.
#include <gtest/gtest.h>

#include <cstring>

#include "core/error.h"
#include "fem/assemble.h"
#include "fem_meshes.h"
#include "tests/io/expect_error.h"

namespace tissuemesh::fem {
namespace {

TetMesh two_tissue_box()
{
    TetMesh mesh = testing::box_mesh(3, 30.0, 0.2, [](const Vec3& c) { return Label(c[0] < 15 ? 1 : 2); });
    mesh.names = {{0, "background"}, {1, "Skull"}, {2, "csf"}};
    return mesh;
}

TEST(Conductivities, DefaultsByNameAndTableByLabelOrName)
{
    const TetMesh mesh = two_tissue_box();
    const Conductivities defaults = resolve_conductivities(mesh, {});
    EXPECT_EQ(defaults.by_label.at(1)[0], 0.01); // "Skull" matches "skull" case-insensitively
    EXPECT_EQ(defaults.by_label.at(2)[4], 1.79);
    const Conductivities table = resolve_conductivities(mesh, {{"1", isotropic(0.02)}, {"CSF", isotropic(1.5)}});
    EXPECT_EQ(table.by_label.at(1)[8], 0.02);
    EXPECT_EQ(table.by_label.at(2)[0], 1.5);
    EXPECT_EQ(table.by_label.at(2)[1], 0.0);
}

TEST(Conductivities, UnknownAndMissingTissuesAreInputErrors)
{
    const TetMesh mesh = two_tissue_box();
    // A tissue the mesh does not have must be refused.
    testing::expect_error<InputError>(
        [&] {
            resolve_conductivities(mesh, {{"scalp", isotropic(0.43)}});
        },
        {"'scalp' is no tissue of the mesh", "2 (csf)"});
    // Without defaults, csf has no conductivity.
    testing::expect_error<InputError>(
        [&] {
            resolve_conductivities(mesh, {{"1", isotropic(0.01)}}, false);
        },
        {"tissue 2 (csf) has no conductivity"});
    EXPECT_THROW(resolve_conductivities(mesh, {{"1", isotropic(-1)}}), InputError);
    EXPECT_THROW(resolve_conductivities(mesh, {{"1", {1, 0.5, 0, 0, 1, 0, 0, 0, 1}}}), InputError); // not symmetric
}

TEST(Conductivities, PatternsFillWhatPlainKeysLeaveMostSpecificFirst)
{
    // A torso-like set of names: patterns for families of tissues, "*" for the rest.
    TetMesh mesh =
        testing::box_mesh(4, 40.0, 0.2, [](const Vec3& c) { return Label(1 + (c[0] < 20) + 2 * (c[1] < 20)); });
    mesh.names = {{1, "rib_left_7"}, {2, "rib_right_7"}, {3, "Lung_upper_lobe_left"}, {4, "liver"}};
    const Conductivities sigma = resolve_conductivities(mesh,
                                                        {{"rib_*", isotropic(0.02)},
                                                         {"rib_right_*", isotropic(0.03)},
                                                         {"lung*", isotropic(0.04)},
                                                         {"*", isotropic(0.2)},
                                                         {"liver", isotropic(0.028)}},
                                                        false);
    EXPECT_EQ(sigma.by_label.at(1)[0], 0.02);  // rib_* (and *)
    EXPECT_EQ(sigma.by_label.at(2)[0], 0.03);  // rib_right_* is more specific than rib_*
    EXPECT_EQ(sigma.by_label.at(3)[0], 0.04);  // case-insensitive
    EXPECT_EQ(sigma.by_label.at(4)[0], 0.028); // a plain key beats every pattern
    // Two equally specific patterns with different values must be refused.
    testing::expect_error<InputError>(
        [&] {
            resolve_conductivities(mesh, {{"r*", isotropic(0.02)}, {"*7", isotropic(0.03)}, {"*", isotropic(0.2)}},
                                   false);
        },
        {"with different values"});
    // A pattern that matches nothing is a mistake.
    testing::expect_error<InputError>(
        [&] {
            resolve_conductivities(mesh, {{"heart*", isotropic(0.2)}, {"*", isotropic(0.2)}}, false);
        },
        {"'heart*' matches no tissue"});
}

// A table that names one tissue twice, by number and by name, had one value win silently (the map's order).
TEST(Conductivities, ATissueNamedTwiceIsAnInputError)
{
    const TetMesh mesh = two_tissue_box();
    // Naming csf twice must be refused.
    testing::expect_error<InputError>(
        [&] {
            resolve_conductivities(mesh, {{"2", isotropic(1.79)}, {"CSF", isotropic(0.3)}});
        },
        {"'2' and 'CSF' both name tissue 2 (csf); give it once"});
}

TEST(Assemble, SymmetricRowsSumToZeroAndEnergyOfALinearField)
{
    const TetMesh mesh = two_tissue_box();
    const Mat3 tensor{0.5, 0.1, 0.0, 0.1, 0.3, 0.05, 0.0, 0.05, 0.2};
    const Conductivities sigma = resolve_conductivities(mesh, {{"1", tensor}, {"2", isotropic(2.0)}});
    const SparseMatrix k = assemble_stiffness(mesh, sigma);
    const Eigen::MatrixXd dense(k);
    // Entries are O(sigma * h) = O(1e-2) S; 1e-15 is round-off.
    EXPECT_LT((dense - dense.transpose()).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LT(dense.rowwise().sum().cwiseAbs().maxCoeff(), 1e-15);
    // u = g . x (x in m): u^T K u = sum over tets of V * g^T sigma g, here a box split in two halves.
    const Vec3 g{3.0, -1.0, 2.0}; // V/m
    Eigen::VectorXd u(static_cast<Eigen::Index>(mesh.vertex_count()));
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
        u[static_cast<Eigen::Index>(v)] = dot(g, metres_per_mm * mesh.vertices[v]);
    double expected = 0;
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
        const Mat3& s = sigma.by_label.at(mesh.tet_labels[t]);
        expected += signed_volume(mesh, t) * 1e-9 * dot(g, multiply(s, g));
    }
    EXPECT_NEAR(u.dot(k * u), expected, 1e-12 * expected);
}

TEST(Assemble, SameBytesOnEveryRun)
{
    const TetMesh mesh = two_tissue_box();
    const Conductivities sigma = resolve_conductivities(mesh, {});
    const SparseMatrix a = assemble_stiffness(mesh, sigma);
    const SparseMatrix b = assemble_stiffness(mesh, sigma);
    ASSERT_EQ(a.nonZeros(), b.nonZeros());
    EXPECT_EQ(std::memcmp(a.valuePtr(), b.valuePtr(), sizeof(double) * static_cast<std::size_t>(a.nonZeros())), 0);
    EXPECT_EQ(std::memcmp(a.innerIndexPtr(), b.innerIndexPtr(), sizeof(int) * static_cast<std::size_t>(a.nonZeros())),
              0);
}

TEST(Assemble, InvertedTetIsAnInputError)
{
    TetMesh mesh = testing::box_mesh(1, 10.0);
    std::swap(mesh.tets[2][0], mesh.tets[2][1]);
    // An inverted tet must be refused.
    testing::expect_error<InputError>(
        [&] {
            assemble_stiffness(mesh, resolve_conductivities(mesh, {{"1", isotropic(1)}}));
        },
        {"tet 2 has volume -"});
}

} // namespace
} // namespace tissuemesh::fem

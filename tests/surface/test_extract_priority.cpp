// The thin-tissue priority of extract_interfaces(): a one-voxel CSF layer stays one piece between skull
// and brain, random images keep every invariant, and without a priority nothing changes.
#include <gtest/gtest.h>

#include <functional>
#include <random>

#include "core/error.h"
#include "image/phantom.h"
#include "surface/check_complex.h"
#include "surface/extract_interfaces.h"
#include "tests/surface/complex_checks.h"

namespace tissuemesh {
namespace {

using testing::make_image;
using testing::random_image;

using surface::extract_interfaces;

TEST(ExtractPriority, CsfOf2mmSpheresSeparatesSkullFromBrainEverywhere)
{
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = 2.0});
    const std::map<Label, int> priority{{3, 1}};
    // Without the priority the one-voxel CSF layer is in pieces and skull touches brain through it.
    ASSERT_GT(testing::voxel_components(phantom.image, 3, 0, false), 1u);
    const InterfaceComplex complex = extract_interfaces(phantom.image, {.priority = priority});
    const surface::CheckReport report = surface::check_complex(complex);
    ASSERT_TRUE(report.ok()) << (report.first_error() ? report.first_error()->description : "");
    EXPECT_EQ(testing::priority_components(phantom.image, 3, 0, false, priority), 1u);
    // One CSF piece between two closed surfaces: against the skull outside and the brain inside.
    EXPECT_EQ(report.tissues.at(3).components, 2u);
    std::size_t skull_brain = 0;
    for (const LabelPair& pair : complex.sides)
        skull_brain += (pair.from == 4 && pair.to == 2) || (pair.from == 2 && pair.to == 4);
    EXPECT_EQ(skull_brain, 0u);
    // The brain is enclosed by the CSF alone: its surface is one piece.
    EXPECT_EQ(report.tissues.at(4).components, 1u);
}

TEST(ExtractPriority, RandomImagesWithRandomPrioritiesKeepEveryInvariant)
{
    std::mt19937 random(20261122);
    std::uniform_int_distribution<int> value(-2, 3), coin(0, 1);
    int split_seen = 0;
    for (int trial = 0; trial < 80; ++trial) {
        const LabelImage image = random_image({4, 4, 4}, random, 3);
        std::map<Label, int> priority;
        for (Label label = 0; label <= 3; ++label)
            if (coin(random) && count_labels(image).contains(label)) priority[label] = value(random);
        if (priority.empty()) priority[static_cast<Label>(image.at(0, 0, 0))] = 1;
        const InterfaceComplex complex = extract_interfaces(image, {.priority = priority});
        ASSERT_EQ(testing::invariant_failures(image, complex, 0, true, priority), "") << "trial " << trial;
        const surface::CheckReport report = surface::check_complex(complex);
        ASSERT_TRUE(report.ok()) << "trial " << trial << ": "
                                 << (report.first_error() ? report.first_error()->description : "");
        split_seen += complex.triangle_count() != extract_interfaces(image).triangle_count();
    }
    EXPECT_GT(split_seen, 40); // the rule must actually change most random cases, or this tests nothing
}

TEST(ExtractPriority, CounterWithoutPriorityIsTheFourteenNeighbourhood)
{
    std::mt19937 random(5);
    for (int trial = 0; trial < 30; ++trial) {
        const LabelImage image = random_image({5, 4, 3}, random, 2);
        for (const bool complement : {false, true})
            for (Label label = 0; label <= 2; ++label)
                ASSERT_EQ(testing::priority_components(image, label, 0, complement, {}),
                          testing::voxel_components(image, label, 0, complement))
                    << "trial " << trial;
    }
}

TEST(ExtractPriority, PriorityThatChangesNoCubeChangesNothing)
{
    // A ball: the top label of every non-uniform cube has its corners Kuhn-connected (a convex digital
    // ball has no checkerboard face), so the priority path must give the very same complex.
    const double c = 4.5, r = 3.2;
    const LabelImage image = make_image({10, 10, 10}, [&](int i, int j, int k) {
        return static_cast<Label>((i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c) <= r * r ? 1 : 0);
    });
    const InterfaceComplex plain = extract_interfaces(image);
    const InterfaceComplex ranked = extract_interfaces(image, {.priority = {{0, 1}}});
    EXPECT_EQ(ranked.vertices, plain.vertices);
    EXPECT_EQ(ranked.triangles, plain.triangles);
    EXPECT_EQ(ranked.sides, plain.sides);
}

TEST(ExtractPriority, RejectsPriorityForAnAbsentLabel)
{
    const LabelImage image = make_image({2, 2, 2}, [](int i, int, int) { return static_cast<Label>(i); });
    try {
        (void)extract_interfaces(image, {.priority = {{7, 1}}});
        FAIL() << "expected InputError";
    } catch (const InputError& error) {
        EXPECT_NE(std::string(error.what()).find("priority given for label 7"), std::string::npos) << error.what();
    }
}

} // namespace
} // namespace tissuemesh

// surface::ExtractedTissue, the one home of "which tissue the extracted surface puts at a point": on random
// images, with and without the priority rule, it gives `to` just in front of every triangle of
// extract_interfaces() and `from` just behind it.
#include <gtest/gtest.h>

#include <random>

#include "surface/extract_interfaces.h"
#include "surface/extracted_tissue.h"
#include "tests/surface/complex_checks.h"

namespace tissuemesh {
namespace {

using surface::ExtractedTissue;
using surface::ExtractOptions;
using testing::make_image;
using testing::random_image;

/// Triangles whose two sides ExtractedTissue gets wrong (make_image: index space is world space). The
/// points are 1e-6 voxel off the triangle's centroid: dual points lie on the 1/24-voxel lattice, so every
/// triangle is far wider than that, and no other triangle comes that close to a centroid.
std::size_t wrong_sides(const LabelImage& image, const ExtractOptions& options)
{
    const InterfaceComplex complex = surface::extract_interfaces(image, options);
    const ExtractedTissue tissue(image, options);
    std::size_t wrong = 0;
    for (std::size_t t = 0; t < complex.triangles.size(); ++t) {
        const auto& tri = complex.triangles[t];
        const Vec3 a = complex.vertices[tri[0]], b = complex.vertices[tri[1]], c = complex.vertices[tri[2]];
        const Vec3 normal = cross(b - a, c - a);
        const Vec3 centroid = (1.0 / 3.0) * (a + b + c), offset = (1e-6 / norm(normal)) * normal;
        wrong += tissue.at_index(centroid + offset) != complex.sides[t].to ||
                 tissue.at_index(centroid - offset) != complex.sides[t].from;
    }
    return wrong;
}

TEST(ExtractedTissue, BothSidesOfEveryTriangleOfRandomImages)
{
    std::mt19937 random(20261205);
    for (int trial = 0; trial < 40; ++trial) {
        const LabelImage image = random_image({4, 4, 3}, random, 3);
        ASSERT_EQ(wrong_sides(image, {}), 0u) << "trial " << trial;
    }
}

TEST(ExtractedTissue, BothSidesOfEveryTriangleOfRandomImagesWithPriority)
{
    std::mt19937 random(20261206);
    std::uniform_int_distribution<int> value(-2, 3);
    for (int trial = 0; trial < 40; ++trial) {
        const LabelImage image = random_image({4, 4, 3}, random, 3);
        std::map<Label, int> priority;
        for (const auto& [label, count] : count_labels(image)) priority[label] = value(random);
        ASSERT_EQ(wrong_sides(image, {.priority = priority}), 0u) << "trial " << trial;
    }
}

TEST(ExtractedTissue, KeptTissuesAndBackgroundAsTheExtractionHasThem)
{
    // Tissue 3 not kept: it becomes the background, 5, as does everything outside the image.
    const LabelImage image = make_image({3, 3, 3}, [](int i, int, int) { return static_cast<Label>(i + 1); });
    const ExtractOptions options{.tissues = {1, 2}, .background = 5};
    EXPECT_EQ(wrong_sides(image, options), 0u);
    const ExtractedTissue tissue(image, options);
    EXPECT_EQ(tissue.at_index({0, 1, 1}), 1);
    EXPECT_EQ(tissue.at_index({2, 1, 1}), 5);
    EXPECT_EQ(tissue.at_index({1, 1, -0.9}), 5);
}

} // namespace
} // namespace tissuemesh

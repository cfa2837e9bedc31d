// LabelField: the zero level of blurred tissue indicators lies close to the exact interfaces of a phantom,
// much closer than the terraced voxel boundary; thin layers pull it a little towards their inside.
#include <gtest/gtest.h>

#include <iostream>
#include <random>

#include "image/phantom.h"
#include "surface/detail/label_field.h"

namespace tissuemesh {
namespace {

struct StepFigures {
    double max_voxels = 0;
    double mean_voxels = 0;
};

/// One Newton step from 2000 random points of the exact sphere of `radius_mm` between tissues `inside`
/// and `outside` of spheres4 (centred at the origin): how far it goes, in voxels.
StepFigures steps_from_exact_sphere(const image::Phantom& phantom, double radius_mm, Label inside, Label outside)
{
    const surface::detail::LabelField field(phantom.image, 0, 1.0);
    const double voxel = phantom.image.spacing_mm()[0];
    std::mt19937 random(7);
    std::normal_distribution<double> gauss;
    StepFigures figures;
    for (int i = 0; i < 2000; ++i) {
        Vec3 direction{gauss(random), gauss(random), gauss(random)};
        direction = (1.0 / norm(direction)) * direction;
        const auto step = field.step_to_interface(radius_mm * direction, inside, outside, 1.0);
        EXPECT_TRUE(step.has_value());
        if (!step) continue;
        figures.max_voxels = std::max(figures.max_voxels, norm(*step) / voxel);
        figures.mean_voxels += norm(*step) / voxel / 2000;
    }
    return figures;
}

TEST(LabelField, ZeroLevelHugsTheExactSpheres)
{
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = 2.0});
    const double radii[] = {92, 86, 80, 78};  // scalp|air, skull|scalp, CSF|skull, brain|CSF
    for (int s = 0; s < 4; ++s) {
        const StepFigures figures =
            steps_from_exact_sphere(phantom, radii[s], static_cast<Label>(s + 1), static_cast<Label>(s));
        std::cout << "[ figures  ] spheres4 2 mm, sphere " << radii[s] << " mm: the zero level lies within max/mean "
                  << figures.max_voxels << "/" << figures.mean_voxels << " voxel\n";
        // Measured 0.27 / 0.06 on the two outer spheres and 0.46 / 0.13 on both sides of the CSF, one voxel
        // thick here (the narrow blur; with the wide one the layer pulled the level 0.3 voxel inwards);
        // the terraced voxel boundary is up to 0.87 voxel off.
        EXPECT_LT(figures.max_voxels, 0.5);
        EXPECT_LT(figures.mean_voxels, 0.15);
    }
}

TEST(LabelField, NoStepFarFromBothTissues)
{
    const image::Phantom phantom = image::make_phantom("spheres4", {.voxel_mm = 2.0});
    const surface::detail::LabelField field(phantom.image, 0, 1.0);
    EXPECT_FALSE(field.step_to_interface({0, 0, 0}, 1, 0, 0.5).has_value());  // deep in the brain
}

} // namespace
} // namespace tissuemesh

// Timing on a large complex (label "long": left out of the default run).
#include <chrono>
#include <cstdio>
#include <gtest/gtest.h>

#include "surface/check_complex.h"
#include "tests/support/complexes.h"

namespace tissuemesh {
namespace {

TEST(CheckComplexLong, MillionTriangleIcosphereIsCheckedInSeconds)
{
    // 20 * 4^8 = 1 310 720 triangles.
    const InterfaceComplex complex = testing::icosphere(8, 50.0, {1, 2, 3});
    const auto start = std::chrono::steady_clock::now();
    const surface::CheckReport report = surface::check_complex(complex);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("check_complex: %zu triangles in %.2f s\n", report.triangles, seconds);
    RecordProperty("seconds", std::to_string(seconds));
    EXPECT_TRUE(report.ok());
    EXPECT_EQ(report.triangles, 1310720u);
    EXPECT_EQ(report.tissues.at(1).components, 1u);
    // Generous bound for a loaded 2-core machine; a regression to quadratic behaviour takes hours.
    EXPECT_LT(seconds, 60.0);
}

} // namespace
} // namespace tissuemesh

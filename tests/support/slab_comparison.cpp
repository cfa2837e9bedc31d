#include "tests/support/slab_comparison.h"

#include <cmath>

#include <gtest/gtest.h>

namespace tissuemesh::testing {

void expect_slabs_keep_the_whole(const surface::CheckReport& cut, const surface::CheckReport& whole,
                                 const surface::CheckReport& before)
{
    ASSERT_TRUE(cut.ok()) << (cut.first_error() ? cut.first_error()->description : "");
    ASSERT_EQ(cut.tissues.size(), before.tissues.size());
    for (const auto& [tissue, facts] : before.tissues) {
        EXPECT_EQ(cut.tissues.at(tissue).components, facts.components) << "tissue " << tissue;
        EXPECT_NEAR(cut.tissues.at(tissue).volume_mm3, whole.tissues.at(tissue).volume_mm3,
                    0.01 * std::abs(facts.volume_mm3))
            << "tissue " << tissue;
    }
}

} // namespace tissuemesh::testing

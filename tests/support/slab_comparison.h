// Test helpers: what an edit in slabs (decimate(), remesh() with DecimateOptions::slabs or
// RemeshOptions::slabs) must keep of the same edit over the whole.
#pragma once

#include "surface/check_complex.h"

namespace tissuemesh::testing {

/// Expects the complex edited in slabs (`cut`) valid, with the tissues of the input (`before`), each in as
/// many pieces, and each tissue's volume within 1% of the input's volume of the one edited whole (`whole`):
/// the edits differ only in their order near the cuts.
void expect_slabs_keep_the_whole(const surface::CheckReport& cut, const surface::CheckReport& whole,
                                 const surface::CheckReport& before);

} // namespace tissuemesh::testing

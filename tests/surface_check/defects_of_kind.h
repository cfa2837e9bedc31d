// The defects of one kind in a check report, for tests that look at each of them.
#pragma once

#include <vector>

#include "surface/check_complex.h"

namespace tissuemesh::testing {

/// The defects of `report` of kind `kind`, in the report's order.
inline std::vector<const surface::Defect*> of_kind(const surface::CheckReport& report, surface::DefectKind kind)
{
    std::vector<const surface::Defect*> found;
    for (const surface::Defect& defect : report.defects)
        if (defect.kind == kind) found.push_back(&defect);
    return found;
}

} // namespace tissuemesh::testing

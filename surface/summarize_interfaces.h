// Counts of an interface complex per tissue: what tm-extract reports.
#pragma once

#include <cstddef>
#include <map>

#include "core/interface_complex.h"

namespace tissuemesh::surface {

/// Counts for one tissue.
struct TissueCounts {
    std::size_t triangles = 0;       ///< triangles with this tissue on one side
    std::size_t junction_edges = 0;  ///< edges of its surface where 3 or more tissues meet
};

/// Counts for a whole complex.
struct InterfaceSummary {
    std::map<Label, TissueCounts> tissues;  ///< by label, background included
    std::size_t patches = 0;                ///< distinct unordered tissue pairs
    std::size_t junction_edges = 0;         ///< edges where 3 or more tissues meet
};

/// Counts triangles per tissue and junction edges (an edge whose incident triangles name 3 or more
/// distinct tissues). Near-linear: edge uses bucketed by lower vertex, 8 bytes per triangle corner.
InterfaceSummary summarize_interfaces(const InterfaceComplex& complex);

} // namespace tissuemesh::surface

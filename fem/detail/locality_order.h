// A node order that keeps mesh neighbours close in memory, for the solver's matrix.
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace tissuemesh::fem::detail {

/// The indices of `nodes` (positions in mm, #V) for which `keep[i]` holds, in Z-order (Morton order) of
/// their positions: the bounding box is cut into 2^21 steps per axis and the interleaved bits sort the
/// nodes, ties by index. Neighbouring nodes of a mesh land near each other, so the rows of a matrix in
/// this order touch nearby entries of the vectors (cache reuse in AMG setup, smoothing and products).
/// Deterministic; does not depend on the input order beyond the tie-break.
std::vector<std::uint32_t> locality_order(const std::vector<Vec3>& nodes, const std::vector<bool>& keep);

} // namespace tissuemesh::fem::detail

// Points exactly on the iso-surface of a trilinear field, for measuring how far a surface lies from it.
#pragma once

#include <vector>

#include "surface/snake_field.h"

namespace tissuemesh::testing {

/// Nearest-point distances to the zero level of a trilinear field. Along any line parallel to a grid axis
/// the trilinear interpolant is piecewise linear between voxel planes, so where it changes sign between
/// two planes the linear zero is a point exactly on the iso-surface. Such lines through a sub-grid of
/// `lines_per_voxel` per voxel along the other two axes give a dense sample of the surface; the distance to
/// the nearest sample is then an upper bound of the distance to the surface, too large by at most about
/// half the sample spacing.
class IsoSurfacePoints {
public:
    IsoSurfacePoints(const surface::PotentialField& field, int lines_per_voxel);
    /// Distance (mm) from `p` to the nearest sample (searching up to `max_mm`; returns max_mm beyond).
    double distance(const Vec3& p, double max_mm) const;
    std::size_t size() const { return points_.size(); }

private:
    std::array<std::int64_t, 3> cell_of(const Vec3& p) const;
    std::vector<Vec3> points_;
    Vec3 low_{0, 0, 0};
    double cell_mm_ = 1;
    std::array<std::int64_t, 3> counts_{1, 1, 1};
    std::vector<std::vector<std::uint32_t>> cells_;
};

} // namespace tissuemesh::testing

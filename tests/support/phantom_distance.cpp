#include "tests/support/phantom_distance.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace tissuemesh::testing {

double distance_to_nearest_interface(const image::Phantom& phantom, const Vec3& point, LabelPair pair)
{
    double nearest = std::numeric_limits<double>::max();
    for (const LabelPair& exact : phantom.geometry.interfaces()) {
        const bool same = std::minmax(exact.from, exact.to) == std::minmax(pair.from, pair.to);
        if (same) return phantom.geometry.distance_to_interface(point, exact);
        if (exact.from == pair.from || exact.to == pair.from || exact.from == pair.to || exact.to == pair.to)
            nearest = std::min(nearest, phantom.geometry.distance_to_interface(point, exact));
    }
    return nearest;
}

DistanceFigures phantom_distances(const image::Phantom& phantom, const InterfaceComplex& complex)
{
    std::vector<double> distance;
    std::vector<char> seen(complex.vertices.size(), 0);
    for (std::size_t t = 0; t < complex.triangles.size(); ++t)
        for (const std::uint32_t v : complex.triangles[t]) {
            if (seen[v]) continue;
            seen[v] = 1;
            distance.push_back(distance_to_nearest_interface(phantom, complex.vertices[v], complex.sides[t]));
        }
    DistanceFigures figures;
    const double voxel = phantom.image.spacing_mm()[0];
    for (const double d : distance) {
        figures.max_voxels = std::max(figures.max_voxels, d / voxel);
        figures.mean_voxels += d / voxel / static_cast<double>(distance.size());
    }
    return figures;
}

} // namespace tissuemesh::testing

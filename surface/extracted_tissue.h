// The tissue extract_interfaces()' surfaces put at a point: which side of them the point lies on.
#pragma once

#include <memory>
#include <vector>

#include "core/label_image.h"
#include "core/vec3.h"
#include "surface/extract_interfaces.h"

namespace tissuemesh::surface {

namespace detail {
class PriorityRule;
}

/// Which tissue the surfaces of extract_interfaces(image, options) put at a point of the image.
///
/// The rule (the extraction's surfaces read backwards; tests/surface checks it against both sides of every
/// extracted triangle): the grid cube holding the point (corners at voxel centres, outside the image the
/// background) is cut into the tetrahedra the extraction uses (detail::cube_tetrahedra(): the 6 Kuhn ones,
/// or the priority rule's 12 around the centre of a split cube, the centre labelled with the cube's top
/// tissue). In the tetrahedron holding the point each vertex's label gets the vertex's barycentric weight
/// and the largest sum wins (ties: the smaller label): with 2 tissues that is the side of the midpoint
/// plane the extraction puts there. With 3-4 tissues the extraction fans its surface from the
/// tetrahedron's centroid over the curves on its faces, so the weights are first moved to the point where
/// the ray from the centroid leaves the tetrahedron (the vertex with the smallest weight drops out).
/// extract_surface_nets() has the same tissues per lattice point and the same connectivity; its smoothed
/// surface runs within a voxel of this one.
class ExtractedTissue {
public:
    /// Keeps a reference to `image`, which must outlive this object. `options` as given to extract_interfaces();
    /// they are not checked here (extract_interfaces() checks them).
    explicit ExtractedTissue(const LabelImage& image, const ExtractOptions& options = {});
    ~ExtractedTissue();
    ExtractedTissue(ExtractedTissue&&) noexcept;
    ExtractedTissue& operator=(ExtractedTissue&&) = delete;

    /// The tissue at continuous voxel index `index` (voxel centres at integers; image.world_to_index()
    /// of a point in mm).
    Label at_index(const Vec3& index) const;

private:
    Label corner_label(const Index3& corner) const;

    const LabelImage& image_;
    std::vector<Label> map_;
    Label background_;
    std::unique_ptr<const detail::PriorityRule> rule_; ///< null without a priority
};

} // namespace tissuemesh::surface

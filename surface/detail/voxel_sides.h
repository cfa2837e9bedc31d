// VoxelSides: whether an edit of an interface complex would carry a voxel centre across it.
//
// Surface nets keep every voxel centre on the side of its own tissue (the Dice of the extracted surfaces against
// the voxels is 1), and remeshing then loses most of what the chain loses: on the 1 mm usc19-5 head the CSF's Dice
// fell from 0.979 after decimation to 0.952 after remeshing, at the same tet count (docs/surfaces.md). A move of a
// vertex, or a collapse, replaces the triangles of its star by others on the same link: together they bound the
// region the surface sweeps, and a point lies in it when a ray from the point crosses those triangles an odd
// number of times. Only the centres of voxels with a differently labelled face neighbour are asked: the others lie
// at least half a voxel from every interface the image implies.
//
// Floating point (a ray through an edge or a vertex may count wrongly): a measure of fidelity, not a rule that
// validity depends on, which the editor's own checks keep.
#pragma once

#include <vector>

#include "core/label_image.h"
#include "core/vec3.h"
#include "surface/detail/triangle_distance.h"

namespace tissuemesh::surface::detail {

class VoxelSides {
public:
    explicit VoxelSides(const LabelImage& image);

    /// Whether a voxel centre next to another label lies between `before` and `after`, two sets of triangles over
    /// the same boundary (a star before and after an edit): the edit would put it on the other side.
    bool carries_a_centre(const std::vector<TriangleCorners>& before, const std::vector<TriangleCorners>& after) const;

private:
    const LabelImage& image_;
    std::vector<char> next_to_other_; ///< per voxel: a face neighbour in the image has another label
};

} // namespace tissuemesh::surface::detail

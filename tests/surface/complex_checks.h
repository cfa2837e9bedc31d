// Independent checks of interface complexes for the tests: they know nothing about how the extractor
// works, only about the invariants it promises.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "core/interface_complex.h"
#include "core/label_image.h"

namespace tissuemesh::testing {

/// An image on the unit grid (1 mm voxels, origin 0) whose label at voxel (i, j, k) is `label_of(i, j, k)`.
LabelImage make_image(const Dims& dims, const std::function<Label(int, int, int)>& label_of);

/// An image on the unit grid whose labels are drawn uniformly from 0..`max_label` by `random`, voxel by voxel
/// in storage order (i fastest).
LabelImage random_image(const Dims& dims, std::mt19937& random, Label max_label);

/// The closed surface of one tissue as the tests see it.
struct TissueSurfaceFacts {
    std::size_t triangles = 0;
    std::size_t bad_edges = 0;  ///< edges not used exactly once in each direction by the outward surface
    std::size_t components = 0; ///< edge-connected pieces of the outward surface
    double volume_mm3 = 0;      ///< enclosed by the outward surface (divergence theorem)
};

/// Outward surface facts for `tissue`: triangles with `tissue` on one side, flipped so that `tissue`
/// is behind them.
TissueSurfaceFacts tissue_facts(const InterfaceComplex& complex, Label tissue);

/// Triangles that share their vertex set with another triangle.
std::size_t duplicate_triangles(const InterfaceComplex& complex);
/// Triangles whose area is below `min_area_mm2`.
std::size_t degenerate_triangles(const InterfaceComplex& complex, double min_area_mm2);

/// Pairs of triangles that meet other than at shared vertices and shared edges. Exact: needs vertex
/// coordinates that are multiples of 1/24 mm (images with spacing 1, identity direction, integer
/// origin), which holds for the dual points of extract_interfaces. Brute force with a bounding-box
/// filter: small complexes only.
std::size_t intersecting_pairs(const InterfaceComplex& complex);

/// Connected components of the voxels labelled `label` (or, with `complement`, of every other label)
/// in `image` padded by one voxel of `background`, under the 14-neighbourhood of the Freudenthal
/// decomposition: face neighbours, (1,1,0)-type diagonals with equal signs, and +-(1,1,1).
std::size_t voxel_components(const LabelImage& image, Label label, Label background, bool complement);

/// Like voxel_components(), under the priority connectivity rule of extract_interfaces() (see
/// ExtractOptions::priority): lattice points are the padded voxel centres and the centres of split cubes,
/// joined by the edges of the rule's tetrahedralization. With an empty `priority` it equals
/// voxel_components(). Re-implemented from the header's text (tests/surface/priority_components.cpp).
std::size_t priority_components(const LabelImage& image, Label label, Label background, bool complement,
                                const std::map<Label, int>& priority);

/// Non-uniform grid cubes (corners at voxel centres, padded image) having `label` at a corner: the only
/// places where a dual surface and the voxel-cube boundary can differ, so |volume - voxels| is at most
/// this count times the voxel volume.
std::size_t boundary_cubes(const LabelImage& image, Label label, Label background);

/// Runs every invariant on `complex` extracted from `image` and returns the failures, one per line
/// (empty: all good). `exact_intersections` enables intersecting_pairs(). `priority`: the one given to
/// extract_interfaces (surface pieces are then predicted by priority_components()).
std::string invariant_failures(const LabelImage& image, const InterfaceComplex& complex, Label background,
                               bool exact_intersections, const std::map<Label, int>& priority = {});

} // namespace tissuemesh::testing

// LayerSizing: target edge lengths from the thickness of the tissue layers an interface complex bounds.
//
// A tet mesh that keeps the interfaces fills a layer thinner than its surface edges with tets whose four
// nodes lie on the layer's two sides: flat ones. On the 1 mm usc19-5 head, 74% of the tets under 17 degrees
// after tm-tetra had all four nodes on interfaces, in CSF thinner than the 2.4 mm edges, and the worst lay
// where the CSF tapers out between skull and grey matter. Edges no longer than a small multiple of the local
// thickness give those layers tets of a shape, and a field that grows by at most a fixed rate away from thin
// places grades the edges towards them instead of jumping.
//
// The thickness at a triangle is measured along its normal, into each tissue on its sides (the background
// excepted): the distance to the first other triangle the ray meets. Floating point: a measure for sizing,
// not a decision the topology depends on.
#pragma once

#include <cstdint>
#include <vector>

#include "core/interface_complex.h"
#include "core/vec3.h"

namespace tissuemesh::surface::detail {

struct LayerSizingOptions {
    double target_edge_mm = 0; ///< the edge length away from thin layers (the field's largest value)
    double edges_per_mm = 0;   ///< edge length per mm of layer thickness (0: no sizing field)
    double min_edge_mm = 0;    ///< the field's smallest value
    double growth = 0.5;       ///< how much the field may grow per mm away from a thin place
};

class LayerSizing {
public:
    LayerSizing() = default;
    /// The field of `complex` (its background not measured); empty when options.edges_per_mm is 0.
    LayerSizing(const InterfaceComplex& complex, Label background, const LayerSizingOptions& options);

    /// The target edge length at p (the options' target where no layer is thin, or with no field).
    double at(const Vec3& p) const;
    /// Triangles whose layer was thinner than the target allows (for the report).
    std::size_t thin_triangles() const { return thin_triangles_; }
    double smallest_mm() const;

private:
    double target_mm_ = 0;
    Vec3 origin_{0, 0, 0};
    double cell_mm_ = 1;
    std::array<std::int64_t, 3> counts_{0, 0, 0};
    std::vector<float> size_; ///< per cell, the target edge (mm)
    std::size_t thin_triangles_ = 0;
};

} // namespace tissuemesh::surface::detail

#include "surface/extract_surface_nets.h"

#include <cmath>

#include "core/error.h"
#include "surface/detail/extraction_labels.h"
#include "surface/detail/net_smoother.h"
#include "surface/detail/surface_net.h"

namespace tissuemesh::surface {

InterfaceComplex extract_surface_nets(const LabelImage& image, const ExtractOptions& options,
                                      const NetSmoothOptions& smoothing, const Progress& progress,
                                      SurfaceNetsReport* report)
{
    detail::validate(smoothing);
    const detail::ExtractionLabels labels =
        detail::prepare_extraction(image, options.tissues, options.background, options.priority, 0, "surface nets");
    detail::SurfaceNet net = detail::build_surface_net(image, labels.map, options.background, options.priority);
    SurfaceNetsReport local;
    SurfaceNetsReport& out = report ? *report : local;
    out = {};
    out.mixed_cubes = net.mixed_cubes;
    out.fallback_cubes = net.fallback_cubes;
    progress.info("extract", concat(net.mixed_cubes, " mixed cubes (", net.fallback_cubes, " kept as tetrahedra), ",
                                    net.triangles.size(), " triangles, ", net.positions.size(), " vertices"));
    const std::vector<Vec3> start = net.positions;
    if (smoothing.iterations > 0)
        detail::smooth_net(net, image, labels.map, options.background, smoothing, progress, out);

    InterfaceComplex complex;
    complex.names = image.names();
    complex.background = options.background;
    complex.vertices.resize(net.positions.size());
    double sum = 0;
    for (std::size_t v = 0; v < net.positions.size(); ++v) {
        complex.vertices[v] = image.index_to_world(net.positions[v]);
        const double moved = distance(complex.vertices[v], image.index_to_world(start[v]));
        sum += moved;
        out.max_displacement_mm = std::max(out.max_displacement_mm, moved);
    }
    out.mean_displacement_mm = net.positions.empty() ? 0 : sum / static_cast<double>(net.positions.size());
    // A direction matrix with a negative determinant mirrors index space: keep normals from `from` to `to`.
    if (determinant(image.direction()) < 0)
        for (Triangle& t : net.triangles) std::swap(t[1], t[2]);
    complex.triangles = std::move(net.triangles);
    complex.sides = std::move(net.sides);
    std::vector<bool> seen(std::size_t{1} << 16, false);
    for (const LabelPair& pair : complex.sides) seen[pair.from] = seen[pair.to] = true;
    for (const Label tissue : labels.tissues) {
        if (!seen[tissue])
            throw AlgorithmError(concat("surface nets: tissue ", tissue,
                                        " produced no triangles; this is a bug, "
                                        "please report it with the image"));
    }
    return complex;
}

} // namespace tissuemesh::surface

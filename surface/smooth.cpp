#include "surface/smooth.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "surface/detail/complex_editor.h"
#include "surface/detail/mesh_measures.h"
#include "surface/detail/voxel_evidence.h"

namespace tissuemesh::surface {
namespace {

using detail::ComplexEditor;
using detail::VertexKind;

void validate(const SmoothOptions& options)
{
    if (!(options.lambda > 0 && options.lambda < 1 && options.mu < -options.lambda && options.mu > -1))
        throw InputError(concat("smooth: lambda ", options.lambda, " and mu ", options.mu,
                                " must satisfy 0 < lambda < -mu < 1 (Taubin); try 0.63 and -0.67"));
    if (!(options.max_depth_voxels > 0 && options.max_depth_voxels <= 1))
        throw InputError(concat("smooth: max depth ", options.max_depth_voxels, " voxels is outside (0, 1]"));
    if (!(options.min_gap_voxels >= 0 && options.min_gap_voxels < 1))
        throw InputError(concat("smooth: min gap ", options.min_gap_voxels, " voxels is outside [0, 1)"));
}

/// The umbrella vector: mean of the neighbours the vertex is smoothed towards, minus its position. Inside
/// a patch only its component along the vertex normal: the tangential part would only slide vertices
/// over the surface (and the marching-cubes triangles are already well shaped; remeshing is a later step),
/// so flat places do not move at all and cost nothing.
Vec3 umbrella(const ComplexEditor& editor, std::uint32_t v)
{
    const bool curve = editor.kind(v) == VertexKind::curve;
    const std::vector<std::uint32_t> ring = curve ? editor.curve_neighbours(v) : editor.neighbours(v);
    Vec3 mean{0, 0, 0};
    for (const std::uint32_t u : ring) mean = mean + editor.position(u);
    const Vec3 shift = (1.0 / static_cast<double>(ring.size())) * mean - editor.position(v);
    if (curve) return shift;
    Vec3 normal{0, 0, 0};
    for (const std::uint32_t t : editor.star(v)) {
        const detail::TriangleCorners c = editor.corners(t);
        normal = normal + cross(c[1] - c[0], c[2] - c[0]);
    }
    const double length = norm(normal);
    if (length == 0) return shift;
    const Vec3 n = (1.0 / length) * normal;
    return dot(shift, n) * n;
}

/// One Jacobi step of factor `factor`: displacements from the current positions, applied vertex by
/// vertex with the checks.
void step(ComplexEditor& editor, const detail::VoxelEvidence& evidence, const std::vector<std::vector<Label>>& tissues,
          double factor, SmoothReport& report)
{
    std::vector<Vec3> shift(editor.vertex_slots(), Vec3{0, 0, 0});
    for (std::uint32_t v = 0; v < editor.vertex_slots(); ++v)
        if (editor.kind(v) != VertexKind::corner && editor.vertex_alive(v)) shift[v] = factor * umbrella(editor, v);
    for (std::uint32_t v = 0; v < editor.vertex_slots(); ++v) {
        if (editor.kind(v) == VertexKind::corner || !editor.vertex_alive(v)) continue;
        if (dot(shift[v], shift[v]) < 1e-20) continue;  // flat here: nothing to do
        Vec3 target = editor.position(v) + shift[v];
        if (!evidence.allows(target, tissues[v])) {
            target = editor.position(v) + 0.5 * shift[v];
            if (!evidence.allows(target, tissues[v])) {
                ++report.refused_by_image;
                continue;
            }
        }
        if (editor.try_move(v, target)) ++report.moves;
        else ++report.refused_by_checks;
    }
}

} // namespace

SmoothReport smooth(InterfaceComplex& complex, const LabelImage& image, const SmoothOptions& options,
                    const Progress& progress)
{
    validate(options);
    validate_indices(complex, "smooth input");
    SmoothReport report;
    const Vec3& spacing = image.spacing_mm();
    const double voxel = std::min({spacing[0], spacing[1], spacing[2]});
    const std::vector<Vec3> start = complex.vertices;
    const double cell_mm = 2 * detail::mean_edge_length(complex);
    const Label background = complex.background;
    ComplexEditor editor(std::move(complex),
                         {.min_angle_deg = options.min_angle_deg,
                          .max_normal_change_deg = options.max_normal_change_deg,
                          .min_gap_mm = options.min_gap_voxels * voxel},
                         cell_mm);
    const detail::VoxelEvidence evidence(image, background, options.max_depth_voxels);
    std::vector<std::vector<Label>> tissues(editor.vertex_slots());
    for (std::uint32_t v = 0; v < editor.vertex_slots(); ++v) {
        tissues[v] = tissues_around(editor, v);
        if (editor.vertex_alive(v) && editor.kind(v) == VertexKind::corner) ++report.fixed_vertices;
    }
    for (std::size_t i = 0; i < options.iterations; ++i) {
        step(editor, evidence, tissues, options.lambda, report);
        step(editor, evidence, tissues, options.mu, report);
        ++report.iterations;
        progress.update("smooth", static_cast<double>(i + 1) / static_cast<double>(options.iterations));
    }
    complex = editor.result();
    std::size_t counted = 0;
    for (std::uint32_t v = 0; v < start.size(); ++v) {
        if (!editor.vertex_alive(v)) continue;
        const double d = distance(start[v], editor.position(v));
        report.mean_displacement_mm += d;
        report.max_displacement_mm = std::max(report.max_displacement_mm, d);
        ++counted;
    }
    if (counted > 0) report.mean_displacement_mm /= static_cast<double>(counted);
    progress.info("smooth", concat(report.moves, " moves in ", report.iterations, " iterations; ",
                                   report.refused_by_image, " refused by the image, ", report.refused_by_checks,
                                   " by the validity checks"));
    return report;
}

} // namespace tissuemesh::surface

#include "render/render_section.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "core/error.h"
#include "render/detail/section_frame.h"
#include "render/tissue_colours.h"

namespace tissuemesh::render {
using detail::Point2;

Canvas render_section(const TetMesh& mesh, const LabelImage* image, const std::vector<double>* error_volume_mm3,
                      const SectionViewOptions& options, SectionViewReport* report)
{
    const double w = static_cast<double>(options.width_px), h = static_cast<double>(options.height_px);
    const detail::SectionFrame frame =
        detail::fit_section(mesh, options.axis, options.at_centre, options.position_mm, w, h, "section view");
    if (error_volume_mm3 && error_volume_mm3->size() != mesh.tets.size())
        throw InputError(
            concat("section view: ", error_volume_mm3->size(), " error volumes for ", mesh.tets.size(), " tets"));
    const int axis = options.axis;
    const double at = frame.at;

    Canvas canvas(options.width_px, options.height_px, {255, 255, 255});
    std::set<Label> shown;
    if (image) {
        for (std::size_t y = 0; y < options.height_px; ++y)
            for (std::size_t x = 0; x < options.width_px; ++x) {
                const Vec3 index =
                    image->world_to_index(frame.to_world(static_cast<double>(x) + 0.5, static_cast<double>(y) + 0.5));
                const Index3 voxel{std::llround(index[0]), std::llround(index[1]), std::llround(index[2])};
                if (!image->contains(voxel)) continue;
                const Label label = image->at(voxel[0], voxel[1], voxel[2]);
                canvas.set(static_cast<long>(x), static_cast<long>(y),
                           label == 0 ? Rgb{225, 225, 225} : mix({255, 255, 255}, tissue_colour(label), 0.35));
            }
    }
    const double error_threshold = options.min_error_voxels * (image ? image->voxel_volume_mm3() : 1.0);
    SectionViewReport counts{at, 0, 0};
    std::vector<std::vector<Point2>> outlines;
    std::vector<Point2> polygon;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        detail::cut_tet(mesh, t, frame, polygon);
        if (polygon.empty()) continue;
        ++counts.tets_cut;
        for (Point2& p : polygon) p = frame.to_screen(p);
        shown.insert(mesh.tet_labels[t]);
        const bool high_error =
            error_volume_mm3 && (*error_volume_mm3)[t] >= error_threshold && (*error_volume_mm3)[t] > 0;
        counts.tets_highlighted += high_error;
        canvas.fill_polygon(polygon, high_error ? error_colour : tissue_colour(mesh.tet_labels[t]),
                            high_error ? 0.85 : options.tet_opacity);
        outlines.push_back(polygon);
    }
    const Rgb edge_colour{70, 70, 70};
    for (const auto& outline : outlines)
        for (std::size_t e = 0; e < outline.size(); ++e) {
            const Point2 &p = outline[e], &q = outline[(e + 1) % outline.size()];
            canvas.draw_line(p[0], p[1], q[0], q[1], edge_colour, 1);
        }
    if (options.legend) {
        std::vector<LegendEntry> entries = tissue_legend({shown.begin(), shown.end()}, mesh.names);
        if (counts.tets_highlighted > 0)
            entries.push_back({error_colour, concat("error >= ", format_mm(options.min_error_voxels, 2), " voxel")});
        draw_legend(canvas, 8, 8, entries);
    }
    const std::string caption =
        concat("xyz"[axis], " = ", format_mm(at, 1), " mm", options.title.empty() ? "" : "  ", options.title);
    canvas.draw_text(8, static_cast<long>(options.height_px) - 22, caption, {0, 0, 0});
    if (report) *report = counts;
    return canvas;
}

} // namespace tissuemesh::render

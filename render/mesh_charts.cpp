#include "render/mesh_charts.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>

#include "core/error.h"
#include "core/tet_shape.h"
#include "render/charts.h"
#include "render/tissue_colours.h"

namespace tissuemesh::render {

const std::vector<double>& QualityHistograms::radius_edge_edges()
{
    static const std::vector<double> edges{0.6, 0.8, 1, 1.25, 1.5, 2, 3, 5, 10};
    return edges;
}

QualityHistograms quality_histograms(const TetMesh& mesh)
{
    QualityHistograms h;
    std::map<Label, std::size_t> stack;
    for (const Label label : mesh.tet_labels) stack.emplace(label, 0);
    for (auto& [label, index] : stack) index = h.tissues.size(), h.tissues.push_back(label);
    const auto& edges = QualityHistograms::radius_edge_edges();
    h.min_dihedral.assign(18, std::vector<double>(h.tissues.size(), 0));
    h.radius_edge.assign(edges.size(), std::vector<double>(h.tissues.size(), 0));
    h.tets.assign(h.tissues.size(), 0);
    h.min_dihedral_deg.assign(h.tissues.size(), 180);
    h.max_radius_edge_ratio.assign(h.tissues.size(), 0);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const TetShape shape = tet_shape(mesh, t);
        const std::size_t s = stack.at(mesh.tet_labels[t]);
        const auto dihedral_bin = static_cast<std::size_t>(std::clamp(shape.min_dihedral_deg / 5, 0.0, 17.0));
        h.min_dihedral[dihedral_bin][s] += 1;
        // Bins [edge_i, edge_i+1); ratios under the first edge (impossible but for round-off) go to the first.
        const auto upper = std::upper_bound(edges.begin(), edges.end(), shape.radius_edge_ratio);
        const std::size_t ratio_bin = upper == edges.begin() ? 0 : static_cast<std::size_t>(upper - edges.begin()) - 1;
        h.radius_edge[ratio_bin][s] += 1;
        ++h.tets[s];
        h.min_dihedral_deg[s] = std::min(h.min_dihedral_deg[s], shape.min_dihedral_deg);
        h.max_radius_edge_ratio[s] = std::max(h.max_radius_edge_ratio[s], shape.radius_edge_ratio);
    }
    return h;
}

Canvas render_quality_histograms(const TetMesh& mesh, const QualityHistograms& h, std::size_t width_px,
                                 std::size_t height_px, const std::string& title)
{
    std::vector<Rgb> colours;
    for (const Label label : h.tissues) colours.push_back(tissue_colour(label));
    BarChart dihedral{"tets by smallest dihedral angle", "degrees", {}, h.min_dihedral, colours, true};
    for (int b = 0; b < 18; ++b) dihedral.bin_labels.push_back(std::to_string(5 * b));
    BarChart ratio{
        "tets by radius-edge ratio", "circumradius / shortest edge (regular 0.61)", {}, h.radius_edge, colours, true};
    for (const double edge : QualityHistograms::radius_edge_edges()) ratio.bin_labels.push_back(short_number(edge));
    Canvas canvas(width_px, height_px, {255, 255, 255});
    const long w = static_cast<long>(width_px), top = title.empty() ? 0 : 24, legend_w = 180;
    const long half = (w - legend_w) / 2, h_px = static_cast<long>(height_px) - top;
    draw_bar_chart(canvas, {0, top, half, h_px}, dihedral);
    draw_bar_chart(canvas, {half, top, half, h_px}, ratio);
    draw_legend(canvas, 2 * half + 4, top + 30, tissue_legend(h.tissues, mesh.names));
    if (!title.empty()) canvas.draw_text(8, 6, title, {0, 0, 0});
    return canvas;
}

std::vector<RefineLogRow> read_refine_log(const std::filesystem::path& path)
{
    std::ifstream file(path);
    if (!file)
        throw IoError(
            concat(path.string(), ": cannot open the refinement log; check the path (tm-refine --log writes it)"));
    std::string line;
    std::getline(file, line);
    std::map<std::string, std::size_t> column;
    {
        std::stringstream header(line);
        std::size_t index = 0;
        for (std::string name; std::getline(header, name, ',');) column[name] = index++;
    }
    const std::vector<std::string> needed{"iteration",         "nodes",  "tets", "total_error_volume_mm3",
                                          "worst_quality_key", "seconds"};
    for (const std::string& name : needed)
        if (!column.count(name))
            throw InputError(
                concat(path.string(), ": no column \"", name, "\" in the header; is this a tm-refine --log CSV?"));
    std::vector<RefineLogRow> rows;
    for (std::size_t number = 2; std::getline(file, line); ++number) {
        if (line.empty()) continue;
        std::vector<double> values;
        std::stringstream cells(line);
        for (std::string cell; std::getline(cells, cell, ',');) {
            char* end = nullptr;
            values.push_back(std::strtod(cell.c_str(), &end));
            if (cell.empty() || *end != '\0')
                throw InputError(concat(path.string(), ":", number, ": \"", cell, "\" is not a number"));
        }
        auto get = [&](const std::string& name) {
            const std::size_t index = column.at(name);
            if (index >= values.size())
                throw InputError(
                    concat(path.string(), ":", number, ": the row has ", values.size(), " values, the header more"));
            return values[index];
        };
        rows.push_back({get("iteration"), get("nodes"), get("tets"), get("total_error_volume_mm3"),
                        get("worst_quality_key"), get("seconds")});
    }
    if (rows.empty()) throw InputError(concat(path.string(), ": the refinement log has no row"));
    return rows;
}

Canvas render_convergence(const std::vector<RefineLogRow>& rows, std::size_t width_px, std::size_t height_px,
                          const std::string& title)
{
    LineSeries error{{}, {200, 30, 30}}, key{{}, {30, 60, 200}};
    for (const RefineLogRow& row : rows) {
        error.points.push_back({row.nodes, row.total_error_volume_mm3});
        key.points.push_back({row.nodes, row.worst_quality_key});
    }
    Canvas canvas(width_px, height_px, {255, 255, 255});
    const long top = title.empty() ? 0 : 24, w = static_cast<long>(width_px),
               half = (static_cast<long>(height_px) - top) / 2;
    draw_line_chart(canvas, {0, top, w, half}, {"total error volume (mm^3, log)", "nodes", "", {error}, true});
    draw_line_chart(canvas, {0, top + half, w, half}, {"worst quality key (log)", "nodes", "", {key}, true});
    if (!title.empty()) canvas.draw_text(8, 6, title, {0, 0, 0});
    return canvas;
}

} // namespace tissuemesh::render

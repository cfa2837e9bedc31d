// The quality histograms of a tet mesh and the convergence plot of tm-refine, as pictures.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "core/tet_mesh.h"
#include "render/canvas.h"

namespace tissuemesh::render {

/// Tets per quality bin and tissue, the data behind render_quality_histograms().
struct QualityHistograms {
    std::vector<Label> tissues;                    ///< ascending: the stacks of each bar
    std::vector<std::vector<double>> min_dihedral; ///< 18 bins of 5 deg (0-5, ..., 85-90) x tissues
    std::vector<std::vector<double>> radius_edge;  ///< radius_edge_edges.size() bins x tissues
    std::vector<std::size_t> tets;                 ///< per tissue
    std::vector<double> min_dihedral_deg;          ///< per tissue: smallest over its tets
    std::vector<double> max_radius_edge_ratio;     ///< per tissue: largest over its tets
    static const std::vector<double>&
    radius_edge_edges(); ///< lower bin edges 0.6, 0.8, 1, 1.25, 1.5, 2, 3, 5, 10 (last: and above)
};

/// Counts every tet of `mesh` by its smallest dihedral angle and its radius-edge ratio (tet_shape, core/tet_shape.h).
QualityHistograms quality_histograms(const TetMesh& mesh);

/// Two bar charts side by side of `histograms` (from quality_histograms(mesh)): smallest dihedral angle and
/// radius-edge ratio, a bar per tissue in its colour, counts on a log axis (stacked on a linear axis for
/// more than 8 tissues, see BarChart), with a legend (names from the mesh). Default size 1200 x 480 px.
Canvas render_quality_histograms(const TetMesh& mesh, const QualityHistograms& histograms, std::size_t width_px = 1200,
                                 std::size_t height_px = 480, const std::string& title = "");

/// One row of tm-refine's CSV log (volume/refine_log.h).
struct RefineLogRow {
    double iteration = 0, nodes = 0, tets = 0, total_error_volume_mm3 = 0, worst_quality_key = 0, seconds = 0;
};

/// Parses the CSV tm-refine --log writes (columns found by their header names).
/// @throws IoError when the file cannot be read; InputError when a needed column is missing, a value is
///         not a number, or there is no row
std::vector<RefineLogRow> read_refine_log(const std::filesystem::path& path);

/// Error volume (mm^3) and worst quality key against nodes, two panels one above the other, log y axes.
/// Default size 900 x 640 px.
Canvas render_convergence(const std::vector<RefineLogRow>& rows, std::size_t width_px = 900,
                          std::size_t height_px = 640, const std::string& title = "");

} // namespace tissuemesh::render

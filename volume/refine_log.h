// The convergence log of refine() as text: a CSV table and an SVG line plot (the paper's Figure 6).
#pragma once

#include <string>

#include "volume/refine.h"

namespace tissuemesh::volume {

/// One line per round: iteration,nodes,tets,added_nodes,reassessed_tets,total_error_volume_mm3,
/// worst_quality_key,seconds (with a header line).
std::string refine_log_csv(const RefineReport& report);

/// A self-contained SVG (about 640 x 400 px): total error volume (mm^3, left axis) and worst quality key
/// (right axis) against nodes, one polyline each with a point per round. Deterministic text.
std::string refine_plot_svg(const RefineReport& report, const std::string& title);

} // namespace tissuemesh::volume

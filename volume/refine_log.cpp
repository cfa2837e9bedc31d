#include "volume/refine_log.h"

#include <algorithm>
#include <cstdio>
#include <functional>

#include "core/error.h"

namespace tissuemesh::volume {
namespace {

constexpr double width = 640, height = 400;
constexpr double left = 80, right = 80, top = 40, bottom = 50; // margins around the plot area, px

std::string number(double value)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", value);
    return text;
}

/// A polyline of (nodes, value) pairs scaled into the plot area, with a dot per round.
std::string series(const RefineReport& report, double max_nodes, double max_value,
                   const std::function<double(const RefineIteration&)>& value, const std::string& colour)
{
    const double plot_w = width - left - right, plot_h = height - top - bottom;
    std::string points, dots;
    for (const RefineIteration& it : report.iterations) {
        const double x = left + plot_w * static_cast<double>(it.nodes) / max_nodes;
        const double y = top + plot_h * (1 - value(it) / max_value);
        points += number(x) + "," + number(y) + " ";
        dots += concat("<circle cx=\"", number(x), "\" cy=\"", number(y), "\" r=\"2.5\" fill=\"", colour, "\"/>\n");
    }
    return concat("<polyline fill=\"none\" stroke=\"", colour, "\" stroke-width=\"2\" points=\"", points, "\"/>\n",
                  dots);
}

/// Five ticks with labels along one axis: "x" (bottom), "l" (left) or "r" (right).
std::string ticks(char axis, double max_value)
{
    const double plot_w = width - left - right, plot_h = height - top - bottom;
    std::string out;
    for (int k = 0; k <= 4; ++k) {
        const double f = k / 4.0;
        const std::string label = number(f * max_value);
        if (axis == 'x') {
            const double x = left + f * plot_w;
            out += concat("<line x1=\"", number(x), "\" y1=\"", number(height - bottom), "\" x2=\"", number(x),
                          "\" y2=\"", number(height - bottom + 5), "\" stroke=\"black\"/><text x=\"", number(x),
                          "\" y=\"", number(height - bottom + 18), "\" text-anchor=\"middle\">", label, "</text>\n");
            continue;
        }
        const double y = top + (1 - f) * plot_h, x = axis == 'l' ? left : width - right;
        const double dx = axis == 'l' ? -5 : 5;
        out += concat("<line x1=\"", number(x), "\" y1=\"", number(y), "\" x2=\"", number(x + dx), "\" y2=\"",
                      number(y), "\" stroke=\"black\"/><text x=\"", number(x + 2 * dx), "\" y=\"", number(y + 4),
                      "\" text-anchor=\"", axis == 'l' ? "end" : "start", "\">", label, "</text>\n");
    }
    return out;
}

std::string escape(const std::string& text)
{
    std::string out;
    for (const char c : text) out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
    return out;
}

} // namespace

std::string refine_log_csv(const RefineReport& report)
{
    std::string csv =
        "iteration,nodes,tets,added_nodes,reassessed_tets,total_error_volume_mm3,worst_quality_key,seconds\n";
    for (const RefineIteration& it : report.iterations)
        csv += concat(it.iteration, ",", it.nodes, ",", it.tets, ",", it.added_nodes, ",", it.reassessed_tets, ",",
                      it.total_error_volume_mm3, ",", it.worst_quality_key, ",", it.seconds, "\n");
    return csv;
}

std::string refine_plot_svg(const RefineReport& report, const std::string& title)
{
    double max_nodes = 1, max_error = 1e-9, max_key = 1e-9;
    for (const RefineIteration& it : report.iterations)
        max_nodes = std::max(max_nodes, static_cast<double>(it.nodes)),
        max_error = std::max(max_error, it.total_error_volume_mm3), max_key = std::max(max_key, it.worst_quality_key);
    const std::string error_colour = "#c0392b", key_colour = "#2471a3";
    return concat(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"", width, "\" height=\"", height,
        "\" font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
        "<text x=\"", width / 2, "\" y=\"22\" text-anchor=\"middle\" font-size=\"14\">", escape(title), "</text>\n",
        "<rect x=\"", left, "\" y=\"", top, "\" width=\"", width - left - right, "\" height=\"", height - top - bottom,
        "\" fill=\"none\" stroke=\"black\"/>\n", ticks('x', max_nodes), ticks('l', max_error), ticks('r', max_key),
        "<text x=\"", width / 2, "\" y=\"", height - 12, "\" text-anchor=\"middle\">nodes</text>\n",
        "<text x=\"16\" y=\"", height / 2, "\" fill=\"", error_colour,
        "\" text-anchor=\"middle\" transform=\"rotate(-90 16 ", height / 2,
        ")\">total error volume (mm^3)</text>\n<text x=\"", width - 14, "\" y=\"", height / 2, "\" fill=\"", key_colour,
        "\" text-anchor=\"middle\" transform=\"rotate(90 ", width - 14, " ", height / 2,
        ")\">worst quality key</text>\n",
        series(
            report, max_nodes, max_error, [](const RefineIteration& it) { return it.total_error_volume_mm3; },
            error_colour),
        series(
            report, max_nodes, max_key, [](const RefineIteration& it) { return it.worst_quality_key; }, key_colour),
        "</svg>\n");
}

} // namespace tissuemesh::volume

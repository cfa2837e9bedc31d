// The run report: one self-contained HTML page (pictures embedded as data URIs) from a workflow's
// --json summaries and PNG pictures.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace tissuemesh::render {

/// A --json summary of one step, named after its file ("tetra" for tetra.json).
struct ReportStep {
    std::string name;
    nlohmann::json summary; ///< as run_tool writes it: "tool", "status", "seconds", "peak_memory_mb", ...
};

/// A PNG picture for the report, named after its file ("section" for section.png).
struct ReportPicture {
    std::string name;
    std::string png_bytes;
};

/// What a report holds, in the order it shows them.
struct ReportContent {
    std::string title = "tissuemesh run report";
    std::vector<ReportStep> steps;       ///< in pipeline order (see collect_report)
    std::vector<ReportPicture> pictures; ///< in the order to show
};

/// Reads every *.json in `folder` that is a tool summary (an object with "tool") and every *.png. Steps
/// come in pipeline order (prep, extract, smooth, decimate, remesh, tetra, check, assess, refine, solve,
/// render, by the "tool" name; then by file name); pictures as the workflow tells its story (surface,
/// section, potential, field, quality, convergence), then the others by file name.
/// @throws IoError when the folder cannot be read or a summary is malformed; InputError when it holds
///         neither a summary nor a picture
ReportContent collect_report(const std::filesystem::path& folder);

/// The report page: the pictures (base64 data URIs), a per-tissue table for every summary with a
/// "tissues" object (its numeric fields as columns, a colour swatch from the tissue colour table), and a
/// table of the steps (tool, status, seconds, peak MiB, main counts) with the total time. No external
/// resource: it opens offline. Text is HTML-escaped.
std::string report_html(const ReportContent& content);

/// Standard base64 (RFC 4648, with padding).
std::string base64(const std::string& bytes);

} // namespace tissuemesh::render

#include "render/report_html.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>

#include "core/atomic_file.h"
#include "core/error.h"
#include "render/png.h"
#include "render/tissue_colours.h"

namespace tissuemesh::render {
namespace {

std::string escape(const std::string& text)
{
    std::string out;
    for (const char c : text) {
        switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        default: out += c;
        }
    }
    return out;
}

int pipeline_rank(const std::string& tool)
{
    static const std::vector<std::string> order{
        "tm-phantom", "tm-info",  "tm-prep",       "tm-extract", "tm-check-surface", "tm-smooth", "tm-decimate",
        "tm-remesh",  "tm-tetra", "tm-check-mesh", "tm-assess",  "tm-refine",        "tm-solve",  "tm-render"};
    const auto found = std::find(order.begin(), order.end(), tool);
    return static_cast<int>(found - order.begin());
}

std::string number_text(const nlohmann::json& value, const std::string& key)
{
    if (value.is_boolean()) return value.get<bool>() ? "yes" : "no";
    if (value.is_number_integer() || value.is_number_unsigned()) return value.dump();
    if (!value.is_number()) return escape(value.is_string() ? value.get<std::string>() : value.dump());
    char text[32];
    const double v = value.get<double>();
    // Volumes of whole tissues in plain digits (157114.9, not 1.571e+05); small figures to 4 digits.
    std::snprintf(text, sizeof text, key == "dice" ? "%.4f" : std::abs(v) >= 100 ? "%.1f" : "%.4g", v);
    return text;
}

std::string swatch(Label label)
{
    const Rgb c = tissue_colour(label);
    return concat("<span class=\"sw\" style=\"background:rgb(", int(c[0]), ",", int(c[1]), ",", int(c[2]),
                  ")\"></span>");
}

/// A table of the summary's "tissues" object: a row per label, a column per numeric field.
std::string tissue_table(const ReportStep& step)
{
    const nlohmann::json& tissues = step.summary["tissues"];
    std::vector<std::string> columns;
    for (const auto& [label, entry] : tissues.items())
        if (entry.is_object())
            for (const auto& [key, value] : entry.items())
                if ((value.is_number() || value.is_boolean()) &&
                    std::find(columns.begin(), columns.end(), key) == columns.end())
                    columns.push_back(key);
    std::string html = concat("<h3>Tissues: ", escape(step.name), " (", escape(step.summary.value("tool", "")),
                              ")</h3>\n<table>\n<tr><th>label</th><th>tissue</th>");
    for (const std::string& column : columns) html += "<th>" + escape(column) + "</th>";
    html += "</tr>\n";
    for (const auto& [label, entry] : tissues.items()) {
        if (!entry.is_object()) continue;
        const bool numeric =
            !label.empty() && label.size() < 6 && label.find_first_not_of("0123456789") == std::string::npos;
        const std::string mark =
            numeric && std::stoul(label) <= 65535 ? swatch(static_cast<Label>(std::stoul(label))) : "";
        html += concat("<tr><td>", mark, escape(label), "</td><td>", escape(entry.value("name", label)), "</td>");
        for (const std::string& column : columns)
            html += "<td>" + (entry.contains(column) ? number_text(entry[column], column) : std::string()) + "</td>";
        html += "</tr>\n";
    }
    return html + "</table>\n";
}

std::string step_table(const std::vector<ReportStep>& steps)
{
    static const std::vector<std::string> counts{
        "tets", "nodes", "triangles", "output_triangles", "total_error_volume_mm3", "iterations"};
    std::string html = "<h2>Steps</h2>\n<table>\n<tr><th>step</th><th>tool</th><th>status</th><th>seconds</th><th>peak "
                       "MiB</th><th>figures</th></tr>\n";
    double total = 0;
    for (const ReportStep& step : steps) {
        const nlohmann::json& s = step.summary;
        const double seconds = s.value("seconds", 0.0);
        total += seconds;
        std::string figures;
        for (const std::string& key : counts)
            if (s.contains(key) && s[key].is_number())
                figures += (figures.empty() ? "" : ", ") + key + " " + number_text(s[key], key);
        const std::string status = s.value("status", "?");
        html +=
            concat("<tr><td>", escape(step.name), "</td><td>", escape(s.value("tool", "")), "</td><td class=\"",
                   status == "ok" ? "ok" : "bad", "\">", escape(status), "</td><td>", number_text(seconds, "seconds"),
                   "</td><td>", s.contains("peak_memory_mb") ? number_text(s["peak_memory_mb"], "") : "", "</td><td>",
                   escape(figures), "</td></tr>\n");
    }
    return html + concat("<tr><th>total</th><th></th><th></th><th>", number_text(total, "seconds"),
                         "</th><th></th><th></th></tr>\n</table>\n");
}

} // namespace

std::string base64(const std::string& bytes)
{
    static constexpr char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
        std::uint32_t group = 0;
        for (std::size_t k = 0; k < 3; ++k)
            group = group << 8 | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
        for (std::size_t k = 0; k < 4; ++k) out += k <= n ? alphabet[(group >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

ReportContent collect_report(const std::filesystem::path& folder)
{
    if (!std::filesystem::is_directory(folder))
        throw IoError(concat(folder.string(),
                             ": not a folder; give the workflow's output folder (where the --json summaries are)"));
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(folder))
        if (entry.is_regular_file()) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    ReportContent content;
    for (const auto& path : files) {
        if (path.extension() == ".png") {
            content.pictures.push_back({path.stem().string(), read_file_bytes(path)});
        } else if (path.extension() == ".json") {
            std::ifstream in(path);
            nlohmann::json summary = nlohmann::json::parse(in, nullptr, false);
            if (summary.is_discarded())
                throw IoError(concat(path.string(), ": not valid JSON; rerun the step that wrote it"));
            if (summary.is_object() && summary.contains("tool") && summary["tool"].is_string())
                content.steps.push_back({path.stem().string(), std::move(summary)});
        }
    }
    if (content.steps.empty() && content.pictures.empty())
        throw InputError(
            concat(folder.string(),
                   ": no tool summary (.json with \"tool\") and no .png; run the workflow with --json first"));
    // The workflow's pictures in the order of the story (the model, the mesh, the fields, the numbers); others after
    // them.
    const std::vector<std::string> story{"surface", "section", "potential", "field", "quality", "convergence"};
    const auto rank = [&](const ReportPicture& p) {
        return std::find(story.begin(), story.end(), p.name) - story.begin();
    };
    std::stable_sort(content.pictures.begin(), content.pictures.end(),
                     [&](const ReportPicture& a, const ReportPicture& b) { return rank(a) < rank(b); });
    std::stable_sort(content.steps.begin(), content.steps.end(), [](const ReportStep& a, const ReportStep& b) {
        return pipeline_rank(a.summary["tool"].get<std::string>()) <
               pipeline_rank(b.summary["tool"].get<std::string>());
    });
    return content;
}

std::string report_html(const ReportContent& content)
{
    std::string html = concat(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>", escape(content.title),
        "</title>\n<style>\n",
        "body{font-family:sans-serif;margin:2em;color:#222}table{border-collapse:collapse;margin-bottom:1.5em}",
        "td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}td:nth-child(2),th:nth-child(2){text-align:left}",
        "figure{display:inline-block;margin:0 1em 1em 0;vertical-align:top}img{max-width:100%;border:1px solid #ddd}",
        ".sw{display:inline-block;width:0.9em;height:0.9em;margin-right:0.4em;border:1px solid "
        "#555}.ok{color:#070}.bad{color:#b00}\n",
        "</style>\n</head>\n<body>\n<h1>", escape(content.title), "</h1>\n");
    if (!content.pictures.empty()) {
        html += "<h2>Pictures</h2>\n";
        for (const ReportPicture& picture : content.pictures)
            html +=
                concat("<figure><img alt=\"", escape(picture.name), "\" src=\"data:image/png;base64,",
                       base64(picture.png_bytes), "\"><figcaption>", escape(picture.name), "</figcaption></figure>\n");
    }
    bool heading = false;
    for (const ReportStep& step : content.steps) {
        if (!step.summary.contains("tissues") || !step.summary["tissues"].is_object()) continue;
        if (!heading) html += "<h2>Tissues</h2>\n", heading = true;
        html += tissue_table(step);
    }
    if (!content.steps.empty()) html += step_table(content.steps);
    return html + concat("<p>Written by tm-report ", TM_VERSION,
                         ". Colours: render/tissue_colours.h.</p>\n</body>\n</html>\n");
}

} // namespace tissuemesh::render

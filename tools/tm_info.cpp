// tm-info: reports what a label image holds before it is meshed: grid, orientation, and per tissue its
// size, extent, connectivity, contacts and warnings.
#include <cstdio>

#include "core/error.h"
#include "image/label_statistics.h"
#include "io/read_label_image.h"
#include "tools/report_json.h"
#include "tools/run_tool.h"
#include "tools/tissue_arguments.h"

using namespace tissuemesh;

namespace {

std::string join(const std::vector<Label>& labels)
{
    std::string text;
    for (const Label label : labels) {
        if (!text.empty()) text += ',';
        text += std::to_string(label);
    }
    return text.empty() ? "-" : text;
}

std::string vec(const Vec3& v, int digits = 2)
{
    return concat("(", format_mm(v[0], digits), ", ", format_mm(v[1], digits), ", ", format_mm(v[2], digits), ")");
}

void print_report(const std::string& path, const image::LabelStatistics& stats)
{
    const auto& d = stats.dims;
    std::printf("%s\n  dims %zu x %zu x %zu (%zu voxels), spacing %s x %s x %s mm, orientation %s\n", path.c_str(),
                d[0], d[1], d[2], stats.voxel_count, format_mm(stats.spacing_mm[0]).c_str(),
                format_mm(stats.spacing_mm[1]).c_str(), format_mm(stats.spacing_mm[2]).c_str(),
                stats.orientation.c_str());
    std::printf("  origin %s mm, bounds %s .. %s mm\n\n", vec(stats.origin_mm).c_str(), vec(stats.bounds_mm[0]).c_str(),
                vec(stats.bounds_mm[1]).c_str());
    std::printf("%5s  %-16s %10s %13s  %-27s %6s %6s  %-12s %s\n", "label", "name", "voxels", "volume_mm3",
                "bbox (index min..max)", "comp6", "comp26", "touches", "border");
    for (const auto& s : stats.labels) {
        const std::string box = concat(s.index_min[0], ",", s.index_min[1], ",", s.index_min[2], "..", s.index_max[0],
                                       ",", s.index_max[1], ",", s.index_max[2]);
        std::printf("%5u  %-16s %10zu %13.1f  %-27s %6zu %6zu  %-12s %s\n", static_cast<unsigned>(s.label),
                    s.name.c_str(), s.voxels, s.volume_mm3, box.c_str(), s.components6, s.components26,
                    join(s.touches).c_str(), s.border_voxels > 0 ? "yes" : "no");
    }
    std::printf("\n%5s  %-16s %s\n", "label", "name", "bounding box (mm, world axes)");
    for (const auto& s : stats.labels)
        std::printf("%5u  %-16s %s .. %s\n", static_cast<unsigned>(s.label), s.name.c_str(),
                    vec(s.bounds_mm[0]).c_str(), vec(s.bounds_mm[1]).c_str());
    std::size_t warnings = 0;
    for (const auto& s : stats.labels) warnings += s.warnings.size();
    if (warnings > 0) std::printf("\nwarnings:\n");
    for (const auto& s : stats.labels)
        for (const std::string& warning : s.warnings) std::printf("  %s\n", warning.c_str());
}

nlohmann::json summarize(const image::LabelStatistics& stats)
{
    nlohmann::json labels = nlohmann::json::array(), counts = nlohmann::json::object();
    for (const auto& s : stats.labels) {
        nlohmann::json label = s;
        label.update({{"bbox_index_min", s.index_min},
                      {"bbox_index_max", s.index_max},
                      {"bbox_mm_min", s.bounds_mm[0]},
                      {"bbox_mm_max", s.bounds_mm[1]}});
        labels.push_back(label);
        counts[std::to_string(s.label)] = s.voxels;
    }
    nlohmann::json summary = stats;
    summary.update({{"voxel_counts", counts}, {"labels", labels}});
    return summary;
}

// Bytes per voxel besides the file's own, measured on spheres4 at 1 and 2 mm and the 1 mm usc19-5 head
// (docs/robustness.md): the labels, the component maps of the statistics and their queues.
constexpr double bytes_per_voxel = 14;

} // namespace

int main(int argc, char** argv)
{
    std::string input, names;
    image::LabelStatisticsOptions options;
    return tools::run_tool(
        argc, argv,
        {"tm-info",
         "Reports a label image's grid and orientation and, per tissue, voxels, volume, bounding box, connected "
         "components (6/26), touching tissues, and the warnings to act on before meshing (tissue on the image "
         "border, one-voxel-thin places, tiny islands).",
         "Examples:\n  tm-info -i head.nii.gz\n  tm-info head.nii.gz --labels head.labels.json --json info.json\n"
         "  tm-info aseg.mgz --labels FreeSurferColorLUT.txt\n"},
        [&](CLI::App& app) {
            app.add_option("-i,--input,input", input, "Label image")->required()->type_name("IMAGE");
            tools::add_labels_option(app, names)->type_name("FILE");
            app.add_option("--island-voxels", options.island_voxels, "Warn about components under N voxels")
                ->check(CLI::NonNegativeNumber)
                ->capture_default_str();
        },
        [&](tools::ToolContext& ctx) {
            const LabelImage image =
                io::read_label_image(input, {.names_json = names,
                                             .before_voxels = tools::image_memory_check(
                                                 ctx.memory, input, bytes_per_voxel,
                                                 "crop or resample it (tm-prep --crop-pad 2, --spacing-mm 2)")});
            const image::LabelStatistics stats = image::analyze_labels(image, options, ctx.progress);
            print_report(input, stats);
            ctx.summary = summarize(stats);
            ctx.summary["input"] = input;
            ctx.log(concat(stats.labels.size(), " labels in ", stats.voxel_count, " voxels"));
        });
}

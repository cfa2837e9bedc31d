// tm-extract: the interface complex of a label image (multi-material marching cubes), optionally with
// one closed surface per tissue.
#include <cctype>
#include <charconv>
#include <chrono>
#include <filesystem>
#include <optional>
#include <string>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/read_label_image.h"
#include "io/surface_io.h"
#include "io/write_surface_streamed.h"
#include "surface/extract_interfaces.h"
#include "surface/summarize_interfaces.h"
#include "surface/tissue_surface.h"
#include "tools/run_tool.h"

namespace fs = std::filesystem;
using namespace tissuemesh;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// DIR/<label>_<name>.<format>, the name reduced to [A-Za-z0-9_-].
fs::path tissue_path(const fs::path& dir, const InterfaceComplex& complex, Label label, const std::string& format)
{
    std::string name = std::to_string(label);
    const auto named = complex.names.find(label);
    if (named != complex.names.end()) {
        name += "_";
        for (const char c : named->second)
            name += std::isalnum(static_cast<unsigned char>(c)) || c == '-' ? c : '_';
    }
    return dir / (name + "." + format);
}

/// Writes each tissue's outward closed surface (background excluded); returns the paths.
nlohmann::json write_tissue_surfaces(const InterfaceComplex& complex, const surface::InterfaceSummary& summary,
                                     const fs::path& dir, const std::string& format)
{
    fs::create_directories(dir);
    nlohmann::json written = nlohmann::json::array();
    for (const auto& [label, counts] : summary.tissues) {
        if (label == complex.background) continue;
        const fs::path path = tissue_path(dir, complex, label, format);
        io::write_surface(surface::tissue_surface(complex, label), path);
        written.push_back(path.string());
    }
    return written;
}

/// "csf=2", "3=1", ...: tissue (a name from --labels or a number) = integer priority.
std::map<Label, int> parse_priority(const std::vector<std::string>& items, const LabelImage& image)
{
    std::map<Label, int> priority;
    for (const std::string& item : items) {
        const auto eq = item.find('=');
        const std::string tissue = item.substr(0, eq == std::string::npos ? 0 : eq);
        const std::string value = eq == std::string::npos ? "" : item.substr(eq + 1);
        std::optional<Label> label;
        for (const auto& [l, name] : image.names())
            if (name == tissue) label = l;
        int number = 0;
        const auto parse_int = [](const std::string& text, int& out) {
            const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), out);
            return !text.empty() && error == std::errc{} && end == text.data() + text.size();
        };
        if (!label && parse_int(tissue, number) && number >= 0 && number <= 65535) label = static_cast<Label>(number);
        if (!label || !parse_int(value, number))
            throw InputError(concat("--priority ", item, ": expected TISSUE=INTEGER with TISSUE a label number or a "
                                    "name from --labels (e.g. --priority csf=2,3=1)"));
        priority[*label] = number;
    }
    return priority;
}

nlohmann::json priority_summary(const std::map<Label, int>& priority)
{
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [label, value] : priority) out[std::to_string(label)] = value;
    return out;
}

nlohmann::json tissue_summary(const LabelImage& image, const surface::InterfaceSummary& summary)
{
    const auto voxels = count_labels(image);
    nlohmann::json tissues = nlohmann::json::object();
    for (const auto& [label, counts] : summary.tissues) {
        const auto found = voxels.find(label);
        tissues[std::to_string(label)] = {{"name", image.name_of(label)},
                                          {"voxels", found == voxels.end() ? 0 : found->second},
                                          {"triangles", counts.triangles},
                                          {"junction_edges", counts.junction_edges}};
    }
    return tissues;
}

} // namespace

int main(int argc, char** argv)
{
    std::string input, output, per_tissue_dir, per_tissue_format = "stl";
    std::vector<std::string> priority;
    io::ReadImageOptions read_options;
    surface::ExtractOptions options;
    return tools::run_tool(
        argc, argv,
        {"tm-extract",
         "Extracts the interfaces between tissues of a label image as one interface complex: closed, "
         "non-intersecting surfaces, each triangle labelled with the two tissues it separates "
         "(multi-material marching cubes on the Freudenthal tetrahedralization; 14-connectivity). "
         "Writes .ply (binary, label_a/label_b per face) or .vtp by the output's extension.",
         "Examples:\n  tm-extract -i head.nii.gz -o head.ply\n"
         "  tm-extract -i head.nii.gz -o brain.vtp --tissues 4,5 --labels head.json --json extract.json\n"
         "  tm-extract -i head.nii.gz -o head.ply --per-tissue surfaces --per-tissue-format off\n"
         "  tm-extract -i head.nii.gz -o head.ply --labels head.json --priority csf=1\n"},
        [&](CLI::App& app) {
            app.add_option("-i,--input", input, "Label image (.nii, .nii.gz, .nrrd, .mha, ...)")->required();
            app.add_option("-o,--output", output, "Interface complex (.ply or .vtp)")->required();
            app.add_option("--tissues", options.tissues, "Keep only these labels (others become background)")
                ->delimiter(',')->check(CLI::Range(0, 65535));
            app.add_option("--background", options.background, "Background label (also outside the image)")->check(CLI::Range(0, 65535))
                ->capture_default_str();
            app.add_option("--priority", priority,
                           "Thin-tissue priority TISSUE=N (name or label; higher wins ambiguous cubes, keeping a "
                           "one-voxel layer in one piece), e.g. csf=2,3=1")
                ->delimiter(',');
            app.add_option("--labels", read_options.names_json, "Tissue names JSON ({\"1\": \"scalp\"})");
            app.add_option("--per-tissue", per_tissue_dir, "Also write one closed surface per tissue into DIR")
                ->type_name("DIR");
            app.add_option("--per-tissue-format", per_tissue_format, "Format of the per-tissue surfaces")
                ->check(CLI::IsMember({"stl", "off", "ply", "vtp"}))
                ->capture_default_str();
        },
        [&](tools::ToolContext& ctx) {
            const std::string extension = full_extension(output);
            if (extension != ".ply" && extension != ".vtp")
                throw InputError(concat(output, ": the interface complex is written as .ply or .vtp (label pairs "
                                        "per triangle); use --per-tissue for .stl/.off"));
            auto start = std::chrono::steady_clock::now();
            const LabelImage image = io::read_label_image(input, read_options);
            const double read_seconds = seconds_since(start);
            options.priority = parse_priority(priority, image);
            // A lone .ply is written slab by slab as extraction goes, never held whole (the 1 mm head's
            // complex is ~180 MB); .vtp and --per-tissue need the whole complex in memory. Same bytes.
            const bool streamed = extension == ".ply" && per_tissue_dir.empty();
            surface::InterfaceSummarizer counter;
            CollectingSink collector;
            const auto extract = [&](InterfaceSink& sink) {
                TeeSink both(sink, counter);
                tools::with_source(input, [&] { surface::extract_interfaces(image, options, both, ctx.progress); });
            };
            start = std::chrono::steady_clock::now();
            double extract_seconds = 0;
            if (streamed) {
                io::write_surface_streamed(output, [&](InterfaceSink& ply) {
                    extract(ply);
                    extract_seconds = seconds_since(start);
                });
            } else {
                extract(collector);
                extract_seconds = seconds_since(start);
                io::write_surface(collector.complex(), output);
            }
            const surface::InterfaceSummary counts = counter.summary();
            nlohmann::json per_tissue = nlohmann::json::array();
            if (!per_tissue_dir.empty())
                per_tissue = write_tissue_surfaces(collector.complex(), counts, per_tissue_dir, per_tissue_format);
            ctx.log(concat(image.voxel_count(), " voxels -> ", counts.triangles, " triangles, ", counts.vertices,
                           " vertices (", format_mm(extract_seconds, 2), " s)"));
            ctx.summary = {{"input", input},       {"output", output},
                           {"dims", image.dims()}, {"voxels", image.voxel_count()},
                           {"triangles", counts.triangles}, {"vertices", counts.vertices},
                           {"background", options.background},      {"tissues", tissue_summary(image, counts)},
                           {"priority", priority_summary(options.priority)},
                           {"per_tissue", per_tissue},              {"streamed", streamed},
                           {"seconds_read", read_seconds},          {"seconds_extract", extract_seconds},
                           {"seconds_write", seconds_since(start) - extract_seconds}};
        });
}

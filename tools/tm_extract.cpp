// tm-extract: the interface complex of a label image (multi-material marching cubes), optionally with
// one closed surface per tissue.
#include <algorithm>
#include <cctype>
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
#include "surface/extract_surface_nets.h"
#include "surface/summarize_interfaces.h"
#include "surface/tissue_surface.h"
#include "tools/report_json.h"
#include "tools/run_tool.h"
#include "tools/extract_priority.h"
#include "tools/tissue_arguments.h"

namespace fs = std::filesystem;
using namespace tissuemesh;

namespace {

/// DIR/<label>_<name>.<format>, the name reduced to [A-Za-z0-9_-].
fs::path tissue_path(const fs::path& dir, const InterfaceComplex& complex, Label label, const std::string& format)
{
    std::string name = std::to_string(label);
    const auto named = complex.names.find(label);
    if (named != complex.names.end()) {
        name += "_";
        for (const char c : named->second) name += std::isalnum(static_cast<unsigned char>(c)) || c == '-' ? c : '_';
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

// Memory of an extraction, measured on spheres4 at 1 and 2 mm, the thin phantom and the 1 mm usc19-5 head
// (docs/robustness.md): reading holds the file's voxels and 4 B more per voxel (the 1 mm head, streamed to
// .ply: 46 MiB in all, 6 B per voxel); extracting holds the labels and about 65 B per triangle, and marching cubes on
// Freudenthal's tets makes 6-8 triangles per voxel face between two labels, so about 500 B per such face.
constexpr double read_bytes_per_voxel = 4;
constexpr double bytes_per_voxel = 3;
constexpr double bytes_per_label_face = 500;

/// Voxel faces between two different labels, the outside of the image counting as `background`.
double label_faces(const LabelImage& image, Label background)
{
    const Dims& d = image.dims();
    std::size_t faces = 0;
    for (std::size_t k = 0; k < d[2]; ++k)
        for (std::size_t j = 0; j < d[1]; ++j)
            for (std::size_t i = 0; i < d[0]; ++i) {
                const Label label = image.at(i, j, k);
                faces += (i + 1 < d[0] ? label != image.at(i + 1, j, k) : label != background) +
                         (i == 0 && label != background);
                faces += (j + 1 < d[1] ? label != image.at(i, j + 1, k) : label != background) +
                         (j == 0 && label != background);
                faces += (k + 1 < d[2] ? label != image.at(i, j, k + 1) : label != background) +
                         (k == 0 && label != background);
            }
    return static_cast<double>(faces);
}

/// Refuses an extraction that would need more memory than --max-memory allows, before it starts. A streamed
/// extraction (a lone .ply) holds the triangles of two slabs at a time, not all of them.
void check_memory(const tools::ToolContext& context, const std::string& input, const LabelImage& image,
                  Label background, bool streamed)
{
    if (context.memory.bytes == 0) return; // no limit: spare the pass over the voxels
    const double voxels = static_cast<double>(image.voxel_count()), faces = label_faces(image, background);
    const double held_faces =
        streamed ? 2 * faces / static_cast<double>(std::max<std::size_t>(image.dims()[2], 1)) : faces;
    tools::require_memory(context.memory, input, voxels * bytes_per_voxel + held_faces * bytes_per_label_face,
                          concat(tools::format_count(held_faces), " voxel faces between tissues",
                                 streamed ? " in two slabs" : "", " x ", tools::format_bytes(bytes_per_label_face),
                                 " for the triangles"),
                          "crop or resample it (tm-prep --crop-pad 2, --spacing-mm 2)");
}

} // namespace

int main(int argc, char** argv)
{
    std::string input, output, per_tissue_dir, per_tissue_format = "stl", method = "marching-cubes";
    surface::NetSmoothOptions smoothing;
    std::vector<std::string> priority, tissues;
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
         "  tm-extract -i head.nii.gz -o head.ply --labels head.json --priority csf=1\n"
         "  tm-extract -i head.nii.gz -o head.ply --method surface-nets --priority auto\n"},
        [&](CLI::App& app) {
            app.add_option("-i,--input", input, "Label image (.nii, .nii.gz, .nrrd, .mha, ...)")->required();
            app.add_option("-o,--output", output, "Interface complex (.ply or .vtp)")->required();
            app.add_option("--tissues", tissues, "Keep only these tissues, names or labels (others become background)")
                ->delimiter(',');
            app.add_option("--background", options.background, "Background label (also outside the image)")
                ->check(CLI::Range(0, 65535))
                ->capture_default_str();
            app.add_option("--priority", priority,
                           "Thin-tissue priority TISSUE=N (name or label; higher wins ambiguous cubes, keeping a "
                           "one-voxel layer in one piece), e.g. csf=2,3=1; or auto: every tissue ranked by its mean "
                           "thickness in the image, the thinnest first")
                ->delimiter(',');
            app.add_option("--method", method,
                           "marching-cubes: the dual of Freudenthal's tetrahedra, 6-8 triangles per voxel face, "
                           "unsmoothed; surface-nets: one vertex per grid cube, about 2 triangles per voxel face, "
                           "smoothed inside its cube (no tm-smooth needed). Same topology, same rules")
                ->check(CLI::IsMember({"marching-cubes", "surface-nets"}))
                ->capture_default_str();
            app.add_option("--smooth-iterations", smoothing.iterations,
                           "surface-nets: Taubin lambda|mu pairs (0: vertices at the cube centres)")
                ->check(CLI::Range(0, 10000))
                ->capture_default_str();
            app.add_option("--margin-voxels", smoothing.margin_voxels,
                           "surface-nets: distance a vertex keeps from its cube's faces (voxels)")
                ->check(CLI::Range(0.01, 0.4))
                ->capture_default_str();
            app.add_option("--max-depth-voxels", smoothing.max_depth_voxels,
                           "surface-nets: a vertex stays within this distance of the voxels of each of its tissues")
                ->check(CLI::Range(0.01, 1.0))
                ->capture_default_str();
            tools::add_labels_option(app, read_options.names_json);
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
            read_options.before_voxels = tools::image_memory_check(
                ctx.memory, input, read_bytes_per_voxel, "crop or resample it (tm-prep --crop-pad 2, --spacing-mm 2)");
            const LabelImage image = io::read_label_image(input, read_options);
            const double read_seconds = tools::seconds_since(start);
            // A lone .ply is written slab by slab as extraction goes, never held whole (the 1 mm head's
            // complex is ~180 MB); .vtp and --per-tissue need the whole complex in memory. Same bytes.
            const bool nets = method == "surface-nets";
            const bool streamed = !nets && extension == ".ply" && per_tissue_dir.empty();
            check_memory(ctx, input, image, options.background, streamed);
            const tools::TissueTable table = tools::tissue_table(image, input);
            for (const std::string& tissue : tissues)
                options.tissues.push_back(tools::parse_tissue(tissue, table, "--tissues"));
            options.priority = tools::parse_extract_priority(priority, image, options.background, table, "--priority");
            // "auto" ranks every tissue of the image; only those kept by --tissues are extracted.
            if (priority == std::vector<std::string>{"auto"} && !options.tissues.empty())
                std::erase_if(options.priority, [&](const auto& entry) {
                    return std::find(options.tissues.begin(), options.tissues.end(), entry.first) ==
                           options.tissues.end();
                });
            surface::InterfaceSummarizer counter;
            CollectingSink collector;
            surface::SurfaceNetsReport nets_report;
            const auto extract = [&](InterfaceSink& sink) {
                TeeSink both(sink, counter);
                tools::with_source(input, [&] {
                    if (!nets) return surface::extract_interfaces(image, options, both, ctx.progress);
                    InterfaceComplex complex =
                        surface::extract_surface_nets(image, options, smoothing, ctx.progress, &nets_report);
                    both.start(complex.names, complex.background);
                    both.add({0, complex.vertices, complex.triangles, complex.sides});
                });
            };
            start = std::chrono::steady_clock::now();
            double extract_seconds = 0;
            if (streamed) {
                io::write_surface_streamed(output, [&](InterfaceSink& ply) {
                    extract(ply);
                    extract_seconds = tools::seconds_since(start);
                });
            } else {
                extract(collector);
                extract_seconds = tools::seconds_since(start);
                io::write_surface(collector.complex(), output);
            }
            const surface::InterfaceSummary counts = counter.summary();
            nlohmann::json per_tissue = nlohmann::json::array();
            if (!per_tissue_dir.empty())
                per_tissue = write_tissue_surfaces(collector.complex(), counts, per_tissue_dir, per_tissue_format);
            ctx.log(concat(image.voxel_count(), " voxels -> ", counts.triangles, " triangles, ", counts.vertices,
                           " vertices (", format_mm(extract_seconds, 2), " s)"));
            ctx.summary = {{"input", input},
                           {"output", output},
                           {"dims", image.dims()},
                           {"voxels", image.voxel_count()},
                           {"triangles", counts.triangles},
                           {"vertices", counts.vertices},
                           {"background", options.background},
                           {"tissues", tissue_summary(image, counts)},
                           {"priority", tools::priority_summary(options.priority)},
                           {"per_tissue", per_tissue},
                           {"streamed", streamed},
                           {"seconds_read", read_seconds},
                           {"seconds_extract", extract_seconds},
                           {"seconds_write", tools::seconds_since(start) - extract_seconds},
                           {"method", method}};
            if (nets) {
                nlohmann::json& nets_summary = ctx.summary["surface_nets"] = nets_report;
                nets_summary["smooth_iterations"] = nets_report.iterations;
            }
        });
}
